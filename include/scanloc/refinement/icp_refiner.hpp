#pragma once
// The PCL ICP baseline: what many users would reach for, scored by the same Likelihood Test and
// Likelihood Distance as the chapter's methods so that the results can be compared.

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/refinement/refinement.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

struct IcpOptions {
  // Pairs farther apart than this are not correspondences, metres.
  double max_correspondence_distance_m = 0.5;
  int max_iterations = 50;  // reaching it without meeting a criterion below is "not converged"
  // Stop when an iteration moves the estimate by less than this: squared translation (m²), and
  // 1 − cos(rotation) below the same number (PCL's transformation epsilon).
  double transformation_epsilon = 1e-8;
  // Stop when the mean squared correspondence distance changes by less than this, relatively.
  double euclidean_fitness_epsilon = 1e-10;
  // false: point-to-point (PCL's TransformationEstimation2D); true: point-to-line, the planar
  // point-to-plane, against map normals estimated by PCA over each map point's neighbours.
  bool point_to_plane = false;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// Registers the scan's valid points to the map points within the scan's range_max of the initial
// laser position (a line map sampled every 2 cm, a point map as it is, or the union of both),
// estimating only (x, y, θ). Scores the postures before and after with ScorePosture(scoring).
// converged is PCL's hasConverged() with the iteration cap counted as a failure; an empty map
// view, a scan without valid beams or too few map points near the laser give the initial posture,
// not converged. iterations counts the ICP iterations run.
RefinementResult RefineIcp(const MapView& map, const LaserScan& scan,
                           const Pose2D& T_world_laser_initial, const ScoringOptions& scoring,
                           const IcpOptions& options = {});

}  // namespace scanloc
