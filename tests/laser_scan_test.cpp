#include "scanloc/geometry/laser_scan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace scanloc {
namespace {

TEST(LaserScan, InvalidRangesAreNonFiniteNonPositiveBelowMinOrAtMax) {
  LaserScan scan;
  scan.layout = MakeLayout(7, M_PI, 20.0);
  scan.layout.range_min_m = 0.1;
  scan.ranges_m = {1.0,
                   -1.0,
                   0.0,
                   0.05,
                   20.0,
                   std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()};
  EXPECT_TRUE(scan.IsValid(0));
  for (std::size_t i = 1; i < scan.size(); ++i) EXPECT_FALSE(scan.IsValid(i)) << "beam " << i;
  EXPECT_EQ(scan.CountValid(), 1u);
}

TEST(MakeLayout, FullCircleStopsOneStepShortOfTheFirstBeam) {
  const ScanLayout layout = MakeLayout(2400, 2.0 * M_PI, 20.0);
  EXPECT_EQ(layout.beam_count, 2400u);
  EXPECT_NEAR(layout.angle_increment_rad, 2.0 * M_PI / 2400, 1e-15);
  EXPECT_NEAR(layout.Bearing(0), -M_PI, 1e-12);
  EXPECT_NEAR(layout.Bearing(2399), M_PI - 2.0 * M_PI / 2400, 1e-12);
}

TEST(MakeLayout, PartialFieldOfViewIncludesBothEnds) {
  const ScanLayout layout = MakeLayout(181, M_PI, 80.0);
  EXPECT_NEAR(layout.Bearing(0), -M_PI / 2, 1e-12);
  EXPECT_NEAR(layout.Bearing(180), M_PI / 2, 1e-12);
}

TEST(LaserScan, CheckConsistentRefusesMismatchedCounts) {
  LaserScan scan;
  scan.layout = MakeLayout(4, M_PI, 20.0);
  scan.ranges_m = {1.0, 1.0, 1.0};
  EXPECT_THROW(scan.CheckConsistent(), std::invalid_argument);
  scan.ranges_m.push_back(1.0);
  EXPECT_NO_THROW(scan.CheckConsistent());
  scan.reflectance = {1.0};
  EXPECT_THROW(scan.CheckConsistent(), std::invalid_argument);
}

TEST(LaserMounting, RobotAndLaserPosesRoundTrip) {
  LaserMounting mounting{{0.04, 0.0, 0.0}};
  const Pose2D T_world_robot{1.0, 2.0, M_PI / 2};
  const Pose2D T_world_laser = mounting.LaserPose(T_world_robot);
  EXPECT_NEAR(T_world_laser.x_m, 1.0, 1e-12);
  EXPECT_NEAR(T_world_laser.y_m, 2.04, 1e-12);
  const Pose2D back = mounting.RobotPose(T_world_laser);
  EXPECT_NEAR(back.x_m, 1.0, 1e-12);
  EXPECT_NEAR(back.y_m, 2.0, 1e-12);
}

// The table's r·(cos, sin) must be LaserScan::Point to the bit, and a layout change must rebuild
// it.
TEST(BearingCosines, GiveEachBeamsPointBitForBitAndFollowTheLayout) {
  for (const ScanLayout& layout :
       {MakeLayout(181, M_PI, 80.0), MakeLayout(1081, 1.5 * M_PI, 30.0),
        MakeLayout(181, M_PI, 80.0), MakeLayout(360, 2.0 * M_PI, 10.0)}) {
    LaserScan scan;
    scan.layout = layout;
    scan.ranges_m.assign(layout.beam_count, 0.0);
    for (std::size_t k = 0; k < layout.beam_count; ++k) scan.ranges_m[k] = 0.5 + 0.37 * k;
    const BearingCosines& table = BearingCosinesOf(layout);
    ASSERT_EQ(table.cos.size(), layout.beam_count);
    ASSERT_EQ(table.sin.size(), layout.beam_count);
    for (std::size_t k = 0; k < layout.beam_count; ++k) {
      const Eigen::Vector2d point = scan.Point(k);
      EXPECT_EQ(scan.ranges_m[k] * table.cos[k], point.x()) << k;
      EXPECT_EQ(scan.ranges_m[k] * table.sin[k], point.y()) << k;
    }
  }
}

// The beams in [from, from + span] as ForEachBeamInInterval found them before it skipped the
// shifts that cannot hold a beam: every shift's bounds computed.
std::vector<std::size_t> BeamsInIntervalByEveryShift(const ScanLayout& layout, double from_rad,
                                                     double span_rad) {
  std::vector<std::size_t> beams;
  const double inc = layout.angle_increment_rad;
  const double start = NormalizeAngle(from_rad);
  for (const double shift : {-2.0 * M_PI, 0.0, 2.0 * M_PI}) {
    const double lo = start + shift - layout.angle_min_rad;
    const double first = std::max(0.0, std::ceil(lo / inc - 1e-9));
    const double last = std::min(static_cast<double>(layout.beam_count) - 1.0,
                                 std::floor((lo + span_rad) / inc + 1e-9));
    for (double k = first; k <= last; k += 1.0) beams.push_back(static_cast<std::size_t>(k));
  }
  return beams;
}

// Random intervals, and intervals that end or start a hair (1e-12 to 1e-5 steps) from the first
// and last beams, on a half, a three-quarter and a full turn: the same beams, in the same order.
TEST(ForEachBeamInInterval, VisitsWhatEveryShiftsBoundsGive) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> angle(-4.0, 4.0), unit(0.0, 1.0);
  int visits = 0;
  for (const ScanLayout& layout : {MakeLayout(181, M_PI, 80.0), MakeLayout(1081, 1.5 * M_PI, 30.0),
                                   MakeLayout(360, 2.0 * M_PI, 10.0)}) {
    const double inc = layout.angle_increment_rad;
    const double last_bearing = layout.Bearing(layout.beam_count - 1);
    for (int i = 0; i < 20000; ++i) {
      const double span = (i % 3 == 0 ? unit(rng) * M_PI : unit(rng) * 4.0 * inc);
      const double hair = std::pow(10.0, -12.0 + 7.0 * unit(rng)) * inc * (i % 2 ? 1.0 : -1.0);
      double from = angle(rng);
      if (i % 5 == 1) from = layout.angle_min_rad - span + hair;  // ends at beam 0
      if (i % 5 == 2) from = last_bearing + hair;                 // starts at the last beam
      std::vector<std::size_t> got;
      ForEachBeamInInterval(layout, from, span, [&](std::size_t k) { got.push_back(k); });
      const std::vector<std::size_t> expected = BeamsInIntervalByEveryShift(layout, from, span);
      ASSERT_EQ(got, expected) << "interval " << i << " from " << from << " span " << span;
      const bool any = AnyBeamInInterval(layout, from, span, [](std::size_t) { return true; });
      ASSERT_EQ(any, !expected.empty()) << "interval " << i;
      visits += static_cast<int>(got.size());
    }
  }
  EXPECT_GT(visits, 100000);
}

}  // namespace
}  // namespace scanloc
