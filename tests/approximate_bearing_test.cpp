#include "scanloc/geometry/approximate_bearing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace scanloc {
namespace {

// The error as an angle: at y = −0 with x < 0, std::atan2 says −π and the approximation π.
double AngleError(double y, double x) {
  return std::abs(std::remainder(ApproximateAtan2(y, x) - std::atan2(y, x), 2.0 * M_PI));
}

TEST(ApproximateAtan2, StaysWithinItsBoundOfStdAtan2AtEveryAngleAndScale) {
  // Every angle on a fine sweep, at scales from micrometres to kilometres, the axes and the
  // diagonals included; then random points.
  double worst = 0.0;
  const int steps = 2000000;
  for (int i = 0; i <= steps; ++i) {
    const double angle = -M_PI + 2.0 * M_PI * i / steps;
    for (const double scale : {1e-6, 0.37, 1.0, 29.0, 4e3}) {
      const double x = scale * std::cos(angle), y = scale * std::sin(angle);
      if (x == 0.0 && y == 0.0) continue;
      worst = std::max(worst, AngleError(y, x));
    }
  }
  std::mt19937 rng(4449);
  std::uniform_real_distribution<double> coordinate(-60.0, 60.0);
  for (int i = 0; i < 1000000; ++i) {
    const double x = coordinate(rng), y = coordinate(rng);
    worst = std::max(worst, AngleError(y, x));
  }
  for (const double x : {1.0, -1.0, 0.0})
    for (const double y : {1.0, -1.0, 0.0, -0.0}) {
      if (x == 0.0 && y == 0.0) continue;
      worst = std::max(worst, AngleError(y, x));
    }
  EXPECT_LT(worst, kApproximateAtan2Bound);
  EXPECT_GT(worst, 1e-6);  // the approximation is one: the test would see a looser bound
}

}  // namespace
}  // namespace scanloc
