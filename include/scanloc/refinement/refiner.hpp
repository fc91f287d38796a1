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

RefinementResult Refine(const MapView& map, const LaserScan& scan,
                        const Pose2D& T_world_laser_initial, const ScoringOptions& scoring,
                        const RefinerOptions& options);

}  // namespace scanloc
