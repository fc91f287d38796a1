#include "scanloc/likelihood/likelihood_distance.hpp"

#include <cmath>
#include <stdexcept>

namespace scanloc {

const char* ToString(RobustKernel kernel) {
  switch (kernel) {
    case RobustKernel::kCauchy:
      return "cauchy";
    case RobustKernel::kHuber:
      return "huber";
    case RobustKernel::kTukey:
      return "tukey";
  }
  return "?";
}

RobustKernel ParseRobustKernel(const std::string& name) {
  if (name == "cauchy") return RobustKernel::kCauchy;
  if (name == "huber") return RobustKernel::kHuber;
  if (name == "tukey") return RobustKernel::kTukey;
  throw std::invalid_argument("unknown robust kernel '" + name +
                              "' (expected cauchy, huber or tukey)");
}

void LikelihoodDistanceOptions::Validate() const {
  if (!(scale_m > 0.0) || !std::isfinite(scale_m))
    throw std::invalid_argument("LikelihoodDistanceOptions: scale_m must be positive and finite");
}

double KernelLoss(RobustKernel kernel, double distance_m, double scale_m) {
  const double d = std::abs(distance_m), c = scale_m, u = d / c;
  switch (kernel) {
    case RobustKernel::kCauchy:
      return 0.5 * c * c * std::log1p(u * u);
    case RobustKernel::kHuber:
      return d <= c ? 0.5 * d * d : c * (d - 0.5 * c);
    case RobustKernel::kTukey: {
      if (d >= c) return c * c / 6.0;
      const double v = 1.0 - u * u;
      return c * c / 6.0 * (1.0 - v * v * v);
    }
  }
  return 0.0;
}

double KernelWeight(RobustKernel kernel, double distance_m, double scale_m) {
  const double d = std::abs(distance_m), c = scale_m, u = d / c;
  switch (kernel) {
    case RobustKernel::kCauchy:
      return 1.0 / (1.0 + u * u);
    case RobustKernel::kHuber:
      return d <= c ? 1.0 : c / d;
    case RobustKernel::kTukey: {
      if (d >= c) return 0.0;
      const double v = 1.0 - u * u;
      return v * v;
    }
  }
  return 0.0;
}

LikelihoodDistanceResult RunLikelihoodDistance(const LaserScan& scan,
                                               const SimulatedScan& simulated,
                                               const LikelihoodDistanceOptions& options) {
  options.Validate();
  if (scan.size() != simulated.size())
    throw std::invalid_argument("RunLikelihoodDistance: beam counts differ");
  LikelihoodDistanceResult result;
  double first = 0.0, second = 0.0, loss = 0.0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!scan.IsValid(i) || !simulated.IsValid(i)) continue;
    ++result.valid_pairs;
    const double d = std::abs(scan.ranges_m[i] - simulated.ranges_m[i]);
    const double w = KernelWeight(options.kernel, d, options.scale_m);
    result.weighted_pairs += w;
    first += w * d;
    second += w * d * d;
    loss += KernelLoss(options.kernel, d, options.scale_m);
  }
  if (result.weighted_pairs > 0.0) {
    result.expect_value_m = first / result.weighted_pairs;
    result.dispersion_m2 = second / result.weighted_pairs;
  }
  if (result.valid_pairs > 0) result.cost_m2 = loss / result.valid_pairs;
  return result;
}

}  // namespace scanloc
