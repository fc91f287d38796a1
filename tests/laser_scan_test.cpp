#include "scanloc/geometry/laser_scan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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

}  // namespace
}  // namespace scanloc
