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

// The position std::atan2 gives, as the map's carving computed it before.
double ExactBeamPosition(const Eigen::Vector2d& q, double angle_min, double increment,
                         std::size_t n) {
  return std::round(
      NormalizeAngle(std::atan2(q.y(), q.x()) - angle_min - 0.5 * (n - 1) * increment) / increment +
      0.5 * (n - 1));
}

TEST(NearestBeamPosition, IsStdAtan2sRoundedPositionBitForBitOnEveryLayoutAndAtHalfSteps) {
  // Four layouts (180 and 181 beams over π, 360 over 2π, 1,081 over 270°), points on bearings
  // that sweep every beam and fall within 1e-7 .. 1e-4 rad of each half step, at ranges from 0.1
  // to 80 m, then random points all around (seed 4450).
  struct Layout {
    std::size_t n;
    double fov;
  };
  std::size_t compared = 0, fallbacks_near = 0;
  std::mt19937 rng(4450);
  std::uniform_real_distribution<double> coordinate(-80.0, 80.0);
  for (const Layout layout :
       {Layout{180, M_PI}, Layout{181, M_PI}, Layout{360, 2.0 * M_PI}, Layout{1081, 1.5 * M_PI}}) {
    const double increment =
        layout.fov / static_cast<double>(layout.fov > 6.0 ? layout.n : layout.n - 1);
    const double angle_min = -0.5 * increment * static_cast<double>(layout.n - 1);
    for (std::size_t beam = 0; beam <= layout.n; ++beam)
      for (const double offset : {-1e-4, -1e-5, -1e-6, -1e-7, 0.0, 1e-7, 1e-6, 1e-5, 1e-4})
        for (const double range : {0.1, 3.3, 80.0}) {
          const double bearing = angle_min + (static_cast<double>(beam) - 0.5) * increment + offset;
          const Eigen::Vector2d q(range * std::cos(bearing), range * std::sin(bearing));
          ASSERT_EQ(NearestBeamPosition(q, angle_min, increment, layout.n),
                    ExactBeamPosition(q, angle_min, increment, layout.n))
              << layout.n << " beams, beam " << beam << ", offset " << offset;
          ++compared;
          fallbacks_near += std::abs(offset) < kApproximateAtan2Bound;
        }
    for (int i = 0; i < 200000; ++i) {
      const Eigen::Vector2d q(coordinate(rng), coordinate(rng));
      ASSERT_EQ(NearestBeamPosition(q, angle_min, increment, layout.n),
                ExactBeamPosition(q, angle_min, increment, layout.n));
      ++compared;
    }
  }
  EXPECT_EQ(compared, 4u * 200000u + 27u * (181 + 182 + 361 + 1082));
  EXPECT_GT(fallbacks_near, 0u);
}

}  // namespace
}  // namespace scanloc
