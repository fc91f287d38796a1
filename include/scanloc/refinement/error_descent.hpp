#pragma once
// Error Descent (the chapter's Approximate Localisation, its Chapter 4): a derivative-free pattern
// search over (x, y, θ) driven by the Likelihood Test, the baseline for the Ceres refinement.

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/refinement/refinement.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

// Defaults are the classroom and office trials': 0.04 m / 0.004 rad, 7 levels.
struct ErrorDescentOptions {
  double initial_step_m = 0.04;     // translation step of the first level, metres
  double initial_step_rad = 0.004;  // rotation step of the first level, radians
  // Number of step sizes tried; the step halves at each level, so the last examines postures
  // initial_step / 2^(levels−1) apart (0.04 m / 2^6 = 0.625 mm). In [1, 30].
  int step_levels = 7;
  int max_moves_per_level = 50;  // a level ends after this many moves even if still improving
  // false: the 6 axis neighbours (±x, ±y, ±θ); true: all 26 neighbours of the 3×3×3 stencil.
  bool diagonal_moves = true;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// Refines T_world_laser_initial by Error Descent: from the current posture, scores the postures one
// step away (simulated scan + Likelihood Test, with `scoring`), moves to the neighbour with the
// lowest cost (3.11) = EV + α·(NVP − MP)/NVP, α = `alpha_m` being the validation rules' own
// (ValidationOptions::alpha_m), ties broken by the lower dispersion (3.10), while that improves on
// the current posture, and halves the step when none does, for `options.step_levels` levels.
// iterations counts the postures scored (the initial one included); converged is true when all
// levels were completed within max_moves_per_level, and false for an empty map or a scan without a
// valid beam (the initial posture is then returned unchanged).
RefinementResult RefineErrorDescent(const MapView& map, const LaserScan& scan,
                                    const Pose2D& T_world_laser_initial,
                                    const ScoringOptions& scoring, double alpha_m,
                                    const ErrorDescentOptions& options = {});

}  // namespace scanloc
