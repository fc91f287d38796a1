#include "scanloc/likelihood/likelihood_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace scanloc {
namespace {

TEST(KernelWeight, IsOneAtZeroAndDecreasesSmoothly) {
  for (const auto kernel : {RobustKernel::kCauchy, RobustKernel::kHuber, RobustKernel::kTukey}) {
    EXPECT_DOUBLE_EQ(KernelWeight(kernel, 0.0, 0.1), 1.0) << ToString(kernel);
    double previous = 1.0;
    for (double d = 0.01; d < 0.5; d += 0.01) {
      const double w = KernelWeight(kernel, d, 0.1);
      EXPECT_LE(w, previous + 1e-15) << ToString(kernel) << " at " << d;
      previous = w;
    }
  }
  EXPECT_NEAR(KernelWeight(RobustKernel::kCauchy, 0.1, 0.1), 0.5, 1e-12);
  EXPECT_NEAR(KernelWeight(RobustKernel::kHuber, 0.2, 0.1), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(KernelWeight(RobustKernel::kTukey, 0.2, 0.1), 0.0);
}

TEST(KernelLoss, DerivativeEqualsWeightTimesDistance) {
  for (const auto kernel : {RobustKernel::kCauchy, RobustKernel::kHuber, RobustKernel::kTukey})
    for (const double d : {0.02, 0.07, 0.15, 0.3}) {
      const double h = 1e-6;
      const double derivative =
          (KernelLoss(kernel, d + h, 0.1) - KernelLoss(kernel, d - h, 0.1)) / (2 * h);
      EXPECT_NEAR(derivative, KernelWeight(kernel, d, 0.1) * d, 1e-6) << ToString(kernel) << d;
    }
}

TEST(RunLikelihoodDistance, MomentsEqualHandComputedWeightedSums) {
  LaserScan scan;
  scan.layout = MakeLayout(3, M_PI, 20.0);
  scan.ranges_m = {1.0, 2.1, -1.0};
  SimulatedScan sim;
  sim.layout = scan.layout;
  sim.ranges_m = {1.0, 2.0, 3.0};
  sim.hit_source.assign(3, HitSource::kSegment);
  sim.hit_index.assign(3, 0);
  const auto r = RunLikelihoodDistance(scan, sim, {RobustKernel::kCauchy, 0.1});
  // Distances 0 and 0.1: weights 1 and 1/2.
  EXPECT_EQ(r.valid_pairs, 2);
  EXPECT_NEAR(r.weighted_pairs, 1.5, 1e-12);
  EXPECT_NEAR(r.expect_value_m, 0.05 / 1.5, 1e-12);
  EXPECT_NEAR(r.dispersion_m2, 0.005 / 1.5, 1e-12);
  EXPECT_NEAR(r.cost_m2, 0.5 * 0.01 * std::log(2.0) / 2.0, 1e-12);
}

TEST(ParseRobustKernel, RefusesUnknownNames) {
  EXPECT_EQ(ParseRobustKernel("tukey"), RobustKernel::kTukey);
  EXPECT_THROW(ParseRobustKernel("gauss"), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
