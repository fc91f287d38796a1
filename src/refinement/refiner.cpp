#include "scanloc/refinement/refiner.hpp"

#include <stdexcept>

namespace scanloc {

const char* ToString(RefinementMethod method) {
  switch (method) {
    case RefinementMethod::kCeres:
      return "ceres";
    case RefinementMethod::kErrorDescent:
      return "error-descent";
    case RefinementMethod::kIcp:
      return "icp";
  }
  return "?";
}

RefinementMethod ParseRefinementMethod(const std::string& name) {
  if (name == "ceres") return RefinementMethod::kCeres;
  if (name == "error-descent") return RefinementMethod::kErrorDescent;
  if (name == "icp") return RefinementMethod::kIcp;
  throw std::invalid_argument("unknown refinement method '" + name +
                              "' (expected ceres, error-descent or icp)");
}

RefinementResult Refine(const MapView& map, const LaserScan& scan,
                        const Pose2D& T_world_laser_initial, const ScoringOptions& scoring,
                        double alpha_m, const RefinerOptions& options) {
  switch (options.method) {
    case RefinementMethod::kCeres:
      return RefineCeres(map, scan, T_world_laser_initial, scoring, options.ceres);
    case RefinementMethod::kErrorDescent:
      return RefineErrorDescent(map, scan, T_world_laser_initial, scoring, alpha_m,
                                options.error_descent);
    case RefinementMethod::kIcp:
      return RefineIcp(map, scan, T_world_laser_initial, scoring, options.icp);
  }
  throw std::invalid_argument("Refine: unknown method");
}

}  // namespace scanloc
