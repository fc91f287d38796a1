#pragma once
// One entry point for the three refinement methods, chosen by name.

#include <string>

#include "scanloc/refinement/ceres_refiner.hpp"
#include "scanloc/refinement/error_descent.hpp"
#include "scanloc/refinement/icp_refiner.hpp"

namespace scanloc {

enum class RefinementMethod { kCeres, kErrorDescent, kIcp };
const char* ToString(RefinementMethod method);
// Parses "ceres", "error-descent" or "icp"; throws std::invalid_argument otherwise.
RefinementMethod ParseRefinementMethod(const std::string& name);

struct RefinerOptions {
  RefinementMethod method = RefinementMethod::kCeres;
  CeresRefinerOptions ceres;
  ErrorDescentOptions error_descent;
  IcpOptions icp;
};

// Refines with options.method; `alpha_m` is (3.11)'s α of the validation rules
// (ValidationOptions::alpha_m), Error Descent's criterion.
RefinementResult Refine(const MapView& map, const LaserScan& scan,
                        const Pose2D& T_world_laser_initial, const ScoringOptions& scoring,
                        double alpha_m, const RefinerOptions& options);

}  // namespace scanloc
