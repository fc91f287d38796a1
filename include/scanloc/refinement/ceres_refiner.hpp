#pragma once
// Approximate Localisation by minimising the Likelihood Distance with Ceres: range residuals of
// each valid beam against the local line of the surface it hits, under a robust kernel, with the
// correspondences renewed by re-simulating the scan at each outer iteration.

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

struct CeresRefinerOptions {
  int max_outer_iterations = 15;          // re-simulations (new correspondences)
  int max_solver_iterations = 20;         // Levenberg–Marquardt iterations per outer iteration
  double translation_tolerance_m = 1e-4;  // converged when an outer step moves less than this...
  double rotation_tolerance_rad = 1e-4;   // ...and turns less than this
  IncidenceWeighting incidence = IncidenceWeighting::kCosine;
  double max_incidence_rad = 1.3;         // kNone/kGate: beams more grazing than this are dropped
  // Pairs farther apart than this are left out of the problem (T_Map's role); ≤ 0 uses T_Map.
  double max_residual_m = 0.0;
  int line_fit_neighbours = 8;            // point maps: k nearest points that define a local line
  double line_fit_radius_m = 0.3;         // ...which must lie within this distance of the hit
  double max_line_thickness = 0.2;        // ...and be this linear (√(λmin/λmax) of their spread)
  // Degenerate when the weakest direction of the information matrix (rotation scaled by the
  // median range) carries less than this fraction of the strongest.
  double degeneracy_ratio = 0.01;
  void Validate() const;
};

RefinementResult RefineCeres(const MapView& map, const LaserScan& scan,
                             const Pose2D& T_world_laser_initial, const ScoringOptions& scoring,
                             const CeresRefinerOptions& options = {});

}  // namespace scanloc
