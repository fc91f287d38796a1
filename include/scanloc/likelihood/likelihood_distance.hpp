#pragma once
// §3.5 The Likelihood Distance: the Likelihood Test's moments on the continuous point-to-point
// distances, every valid pair counted with a weight that decreases smoothly with its distance
// (a robust kernel) instead of the hard T_Map cut, so the cost varies smoothly with the posture.

#include <string>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

enum class RobustKernel { kCauchy, kHuber, kTukey };
const char* ToString(RobustKernel kernel);
// Parses "cauchy", "huber" or "tukey"; throws std::invalid_argument otherwise.
RobustKernel ParseRobustKernel(const std::string& name);

struct LikelihoodDistanceOptions {
  RobustKernel kernel = RobustKernel::kCauchy;
  double scale_m = 0.1;  // the kernel's scale c: distances well above it weigh little
  void Validate() const;
};

// ρ(d): the kernel's loss, ≈ d²/2 for d ≪ c.
double KernelLoss(RobustKernel kernel, double distance_m, double scale_m);
// w(d) = ρ'(d)/d: the weight of a pair at distance d, 1 at d = 0, decreasing smoothly.
double KernelWeight(RobustKernel kernel, double distance_m, double scale_m);

struct LikelihoodDistanceResult {
  int valid_pairs = 0;          // NVP
  double weighted_pairs = 0.0;  // Σ w(d): the soft count of match pairs
  double expect_value_m = 0.0;  // Σ w·d / Σ w
  double dispersion_m2 = 0.0;   // Σ w·d² / Σ w
  double cost_m2 = 0.0;         // Σ ρ(d) / NVP: the smooth objective refinement minimises
};

LikelihoodDistanceResult RunLikelihoodDistance(const LaserScan& scan,
                                               const SimulatedScan& simulated,
                                               const LikelihoodDistanceOptions& options = {});

}  // namespace scanloc
