#pragma once
// Approximate Localisation by minimising the Likelihood Distance with Ceres: range residuals of
// each valid beam against the local line of the surface it hits, under a robust kernel, with the
// correspondences renewed by re-simulating the scan at each outer iteration.

#include <Eigen/Core>
#include <optional>
#include <string>

#include "scanloc/refinement/refinement.hpp"

namespace scanloc {

// How a beam's range residual is weighted by its angle of incidence on the surface (the
// chapter's first error source: a range residual grows as 1/cos(incidence)).
enum class IncidenceWeighting {
  kNone,    // plain range residual r − t (grazing beams dominate)
  kCosine,  // (r − t)·cos(incidence): the measured point's distance to the surface's line
  kGate,    // plain range residual, beams beyond max_incidence_rad dropped
};
const char* ToString(IncidenceWeighting weighting);
IncidenceWeighting ParseIncidenceWeighting(const std::string& name);

// Which surface a beam is paired with on a point map (line maps always use the segment the
// simulated beam hits).
enum class PointAssociation {
  kSimulatedHit,     // the map point the simulated beam hits (the chapter's pairing)
  kNearestEndpoint,  // the map points nearest the measured end point at the current posture
};
const char* ToString(PointAssociation association);
PointAssociation ParsePointAssociation(const std::string& name);

// A prior on the laser's posture, such as the odometry's prediction: the refinement minimises
// the Likelihood Distance plus ½Σ(c·dᵢ/σᵢ)², d = (along, across, heading) the posture's difference
// from `mean` in mean's frame and c the kernel's scale (LikelihoodDistanceOptions::scale_m), the
// beams' own unit. Where the scan constrains the posture the beams outweigh it; along a direction
// they leave free (a corridor's axis) the prior holds the posture.
struct PosturePrior {
  Pose2D mean;  // T_world_laser
  // 1/σ per component (1/m, 1/m, 1/rad); 0 leaves that component to the beams alone.
  Eigen::Vector3d inverse_sigma = Eigen::Vector3d::Zero();
};

struct CeresRefinerOptions {
  int max_outer_iterations = 15;   // re-simulations (new correspondences)
  int max_solver_iterations = 20;  // Levenberg–Marquardt iterations per outer iteration
  // Converged when an outer step moves less than this and turns less than that. Real scans
  // re-pair a few beams at every step, so tighter values only add limit cycles.
  double translation_tolerance_m = 1e-3;
  double rotation_tolerance_rad = 1e-3;
  IncidenceWeighting incidence = IncidenceWeighting::kCosine;
  PointAssociation point_association = PointAssociation::kNearestEndpoint;
  double max_incidence_rad = 1.2;  // kGate: beams more grazing than this (69°) are dropped
  // Pairs farther apart than this are left out of the problem (T_Map's role); ≤ 0 uses T_Map.
  double max_residual_m = 0.0;
  // Point maps: the k nearest points of the hit within a radius define its local line, unless
  // their spread is too round (√(λmin/λmax) above max_line_thickness: a corner or a blob). Chosen
  // on the real-scan harness (docs/BENCHMARKS.md): with de-duplicated maps, whose points stand
  // about one cell diagonal apart, 5 neighbours within 0.3 m beat 6–12 within 0.25–0.5 m.
  int line_fit_neighbours = 5;
  double line_fit_radius_m = 0.3;
  double max_line_thickness = 0.8;
  // Degenerate when the weakest direction of the information matrix (rotation scaled by the
  // median range) carries less than this fraction of the strongest.
  double degeneracy_ratio = 0.01;
  // Score the initial posture (a simulated scan and both tests); callers that already did may
  // turn it off, and test_before / distance_before are then left empty.
  bool score_initial = true;
  // Not a configuration key: a caller that has a prior for this scan (the session's motion prior)
  // sets it. The uncertainty and degeneracy verdict stay the beams' alone.
  std::optional<PosturePrior> prior;
  void Validate() const;
};

RefinementResult RefineCeres(const MapView& map, const LaserScan& scan,
                             const Pose2D& T_world_laser_initial, const ScoringOptions& scoring,
                             const CeresRefinerOptions& options = {});

}  // namespace scanloc
