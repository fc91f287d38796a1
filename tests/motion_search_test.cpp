#include "scanloc/session/motion_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace scanloc {
namespace {

constexpr double kInitialM = 1.0, kInitialRad = 0.45, kMaxM = 3.0, kMaxRad = 0.8;

SearchWindow WindowAfter(const std::vector<Pose2D>& motions, MotionSearchOptions options = {}) {
  MotionWindow window(options);
  for (const Pose2D& motion : motions) window.Add(motion);
  return window.Window(Pose2D{1.0, 2.0, 0.5}, kInitialM, kInitialRad, kMaxM, kMaxRad);
}

TEST(MotionWindow, IsTheInitialWindowUntilFiveMotionsAreKnown) {
  const SearchWindow w = WindowAfter(std::vector<Pose2D>(4, Pose2D{0.1, 0.0, 0.02}));
  EXPECT_DOUBLE_EQ(w.half_width_m, kInitialM);
  EXPECT_DOUBLE_EQ(w.half_yaw_rad, kInitialRad);
  EXPECT_DOUBLE_EQ(w.centre.x_m, 1.0);
  EXPECT_DOUBLE_EQ(w.centre.yaw_rad, 0.5);
}

TEST(MotionWindow, IsTheScaleTimesTheLargestRecentMotion) {
  // Motions of 0.1–0.3 m (the largest a 0.3 m step backwards) and turns up to −0.2 rad.
  const SearchWindow w = WindowAfter(
      {{0.1, 0.0, 0.01}, {-0.3, 0.0, 0.0}, {0.0, 0.2, 0.05}, {0.1, 0.1, -0.2}, {0.05, 0.0, 0.0}});
  EXPECT_NEAR(w.half_width_m, 1.5 * 0.3, 1e-12);
  EXPECT_NEAR(w.half_yaw_rad, 1.5 * 0.2, 1e-12);
}

TEST(MotionWindow, IsAtLeastTheMinimaAndAtMostTheCaps) {
  const SearchWindow still = WindowAfter(std::vector<Pose2D>(6, Pose2D{0.001, 0.0, 0.0}));
  EXPECT_DOUBLE_EQ(still.half_width_m, 0.2);
  EXPECT_DOUBLE_EQ(still.half_yaw_rad, 0.1);
  const SearchWindow fast = WindowAfter(std::vector<Pose2D>(6, Pose2D{4.0, 0.0, 2.0}));
  EXPECT_DOUBLE_EQ(fast.half_width_m, kMaxM);
  EXPECT_DOUBLE_EQ(fast.half_yaw_rad, kMaxRad);
}

TEST(MotionWindow, ForgetsTheMotionsBeforeTheLastScans) {
  MotionSearchOptions options;
  options.scans = 5;
  std::vector<Pose2D> motions = {{1.0, 0.0, 0.3}};  // one fast motion, then five slow ones
  for (int i = 0; i < 5; ++i) motions.push_back({0.2, 0.0, 0.1});
  const SearchWindow w = WindowAfter(motions, options);
  EXPECT_NEAR(w.half_width_m, 1.5 * 0.2, 1e-12);
  EXPECT_NEAR(w.half_yaw_rad, 1.5 * 0.1, 1e-12);
}

TEST(MotionSearchOptions, RefusesAScaleOfZeroAndNegativeMinima) {
  MotionSearchOptions options;
  options.scale = 0.0;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options = {};
  options.min_half_width_m = -0.1;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options = {};
  options.frozen_odometry_range_change_m = std::nan("");
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  EXPECT_NO_THROW(MotionSearchOptions{}.Validate());
}

LaserScan Scan(const std::vector<double>& ranges) {
  LaserScan scan;
  scan.layout.beam_count = ranges.size();
  scan.layout.angle_min_rad = -M_PI / 2;
  scan.layout.angle_increment_rad = M_PI / static_cast<double>(ranges.size());
  scan.layout.range_max_m = 10.0;
  scan.ranges_m = ranges;
  return scan;
}

TEST(MedianRangeChange, IsTheMedianOverTheBeamsValidInBoth) {
  // Changes 0, 0.1, 0.2, 0.3, 0.4 on the five beams valid in both (the sixth is a no-return in
  // one scan, the seventh in both).
  const LaserScan a = Scan({1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 20.0});
  const LaserScan b = Scan({1.0, 2.1, 2.8, 4.3, 5.4, 20.0, 20.0});
  const std::optional<double> change = MedianRangeChange(a, b, 5);
  ASSERT_TRUE(change.has_value());
  EXPECT_NEAR(*change, 0.2, 1e-12);
  EXPECT_FALSE(MedianRangeChange(a, b, 6).has_value());  // only five beams valid in both
}

TEST(MedianRangeChange, IsNothingForScansOfDifferentLayouts) {
  const LaserScan a = Scan(std::vector<double>(20, 2.0));
  EXPECT_FALSE(MedianRangeChange(a, Scan(std::vector<double>(21, 2.0))).has_value());
  LaserScan turned = a;
  turned.layout.angle_min_rad += 0.01;
  EXPECT_FALSE(MedianRangeChange(a, turned).has_value());
  EXPECT_DOUBLE_EQ(*MedianRangeChange(a, a), 0.0);
}

Iteration At(const Pose2D& odometry, double range_m) {
  Iteration iteration;
  iteration.scan = Scan(std::vector<double>(30, range_m));
  iteration.odometry = odometry;
  return iteration;
}

TEST(FrozenOdometry, IsSetAsideOnceTheRangesMovedAndUntilTheOdometryMoves) {
  FrozenOdometry frozen(0.1);
  EXPECT_FALSE(frozen.SetAside(At({}, 2.0)));   // the first scan
  EXPECT_FALSE(frozen.SetAside(At({}, 2.05)));  // standing still: the ranges 5 cm apart
  EXPECT_TRUE(frozen.SetAside(At({}, 2.3)));    // the ranges moved, the odometry did not
  EXPECT_TRUE(frozen.SetAside(At({}, 2.0)));    // and from then on it stays aside
  EXPECT_FALSE(frozen.SetAside(At({0.002, 0.0, 0.0}, 2.3)));  // until it moves itself
  EXPECT_FALSE(frozen.SetAside(At({}, 5.0)));
}

TEST(FrozenOdometry, IsNeverSetAsideWhenItMovesOrWithAThresholdOfZero) {
  FrozenOdometry moving(0.1);
  EXPECT_FALSE(moving.SetAside(At({}, 2.0)));
  EXPECT_FALSE(moving.SetAside(At({0.0, 0.0, 0.01}, 3.0)));
  FrozenOdometry believed(0.0);
  EXPECT_FALSE(believed.SetAside(At({}, 2.0)));
  EXPECT_FALSE(believed.SetAside(At({}, 3.0)));
  Iteration none = At({}, 3.0);
  none.odometry.reset();
  FrozenOdometry absent(0.1);
  EXPECT_FALSE(absent.SetAside(none));  // a scan without odometry has nothing to set aside
}

}  // namespace
}  // namespace scanloc
