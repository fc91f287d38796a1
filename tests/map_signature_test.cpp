#include "scanloc/session/map_signature.hpp"

#include <gtest/gtest.h>

#include <random>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/simulation/simulated_scan.hpp"
#include "scanloc/worlds/laser_simulator.hpp"

namespace scanloc {
namespace {

TEST(LaidScanSample, KeepsAtMostItsCapacitySpreadEvenlyOverTheSession) {
  LaidScanSample sample(10);
  const LaserScan scan = [] {
    LaserScan s;
    s.layout = {5, -1.0, 0.5, 0.1, 30.0};
    s.ranges_m = {1.0, 2.0, 3.0, 4.0, 5.0};
    return s;
  }();
  for (std::size_t i = 0; i < 1000; ++i) sample.Add(i, scan, Pose2D(0.01 * i, 0.0, 0.0));
  const auto& entries = sample.entries();
  ASSERT_GE(entries.size(), 5u);
  ASSERT_LT(entries.size(), 10u);
  EXPECT_EQ(entries.front().index, 0u);
  const std::size_t stride = entries[1].index - entries[0].index;
  for (std::size_t k = 1; k < entries.size(); ++k)
    EXPECT_EQ(entries[k].index - entries[k - 1].index, stride) << "entry " << k;
  EXPECT_GE(entries.back().index + 2 * stride, 1000u) << "the sample reaches the session's end";
  EXPECT_EQ(entries.back().scan.ranges_m, scan.ranges_m) << "thinning keeps every kept scan whole";
  EXPECT_DOUBLE_EQ(entries.back().T_world_robot.x_m, 0.01 * entries.back().index);
}

struct LaidWorld {
  LineMap world;
  LaidScanSample sample{50};
  std::vector<Pose2D> postures;
};

// A 12 m × 6 m room with a pillar; 30 scans along its middle (fixed seed).
LaidWorld Room() {
  LaidWorld w;
  const auto wall = [&](double x0, double y0, double x1, double y1) {
    w.world.segments.push_back({{x0, y0}, {x1, y1}});
  };
  wall(0, 0, 12, 0), wall(12, 0, 12, 6), wall(12, 6, 0, 6), wall(0, 6, 0, 0);
  wall(5, 2, 6, 2), wall(6, 2, 6, 3), wall(6, 3, 5, 3), wall(5, 3, 5, 2);
  std::mt19937 rng(7);
  LaserSimulatorOptions laser;
  laser.beam_count = 720;
  for (int i = 0; i < 30; ++i) {
    const Pose2D posture(1.5 + 0.3 * i, 4.5, 0.05 * i);
    w.postures.push_back(posture);
    w.sample.Add(static_cast<std::size_t>(i), SimulateLaser(w.world, posture, laser, rng), posture);
  }
  return w;
}

PointMap Laid(const LaidWorld& w, const Pose2D& offset) {
  PointMap map;
  for (const auto& e : w.sample.entries()) map.InsertScan(e.scan, offset * e.T_world_robot);
  return map;
}

TEST(MapSignature, AMapWhoseWallsWereLaidTwiceFitsItsOwnScansMoreLooselyAndItsBoundSaysSo) {
  const LaidWorld w = Room();
  const PointMap once = Laid(w, {});
  PointMap twice = Laid(w, {});
  for (const auto& e : w.sample.entries())  // a later pass 12 cm and 0.5° off
    twice.InsertScan(e.scan, Pose2D(0.12, -0.08, 0.009) * e.T_world_robot);
  LocalisationOptions options;
  options.validation.max_expect_value_m = 0.005;  // a prior both maps' fits exceed
  const LaserSignatureOptions signature;
  const MapSignature a =
      MeasureMapSignature({nullptr, &once}, w.sample, {}, {}, options, signature);
  const MapSignature b =
      MeasureMapSignature({nullptr, &twice}, w.sample, {}, {}, options, signature);
  // Measured: once, median 0.028 m and bound 0.032 m; twice, 0.048 m and 0.057 m.
  EXPECT_EQ(a.scans, 30u);
  EXPECT_TRUE(a.learned);
  EXPECT_LT(a.median_expect_value_m, 0.03) << "2 cm range noise, one layer of walls";
  EXPECT_GT(b.median_expect_value_m, a.median_expect_value_m + 0.015);
  EXPECT_GT(b.max_expect_value_m, a.max_expect_value_m + 0.02);
  EXPECT_GE(a.max_expect_value_m, a.median_expect_value_m);
}

TEST(MapSignature, ScansMovedByLoopClosureAreJudgedWhereTheCorrectionPutThem) {
  const LaidWorld w = Room();
  const Pose2D shift(0.0, 3.0, 0.2);        // farther than a refinement reaches
  const PointMap shifted = Laid(w, shift);  // the map rendered from corrected postures
  std::vector<std::optional<Pose2D>> corrected;
  for (const Pose2D& p : w.postures) corrected.push_back(shift * p);
  LocalisationOptions options;
  options.validation.max_expect_value_m = 0.005;
  const MapSignature as_laid =
      MeasureMapSignature({nullptr, &shifted}, w.sample, {}, {}, options, {});
  const MapSignature as_corrected =
      MeasureMapSignature({nullptr, &shifted}, w.sample, corrected, {}, options, {});
  EXPECT_LT(as_corrected.median_expect_value_m, 0.03);
  // EV counts the match pairs only (within T_map): the scans refined from where they were laid,
  // 3 m off, fit part of the map loosely (measured 0.039 m against 0.027 m).
  EXPECT_GT(as_laid.median_expect_value_m, as_corrected.median_expect_value_m + 0.008);
}

TEST(MapSignature, TooFewScansOrASignatureThatLearnsNothingLeaveThePrior) {
  LaidWorld w = Room();
  const PointMap once = Laid(w, {});
  LocalisationOptions options;
  options.validation.max_expect_value_m = 0.005;
  LaserSignatureOptions off;
  off.window = 0;
  const MapSignature nothing =
      MeasureMapSignature({nullptr, &once}, w.sample, {}, {}, options, off);
  EXPECT_FALSE(nothing.learned);
  EXPECT_DOUBLE_EQ(nothing.max_expect_value_m, 0.005);
  LaidScanSample few(50);
  for (int i = 0; i < 3; ++i)
    few.Add(i, w.sample.entries()[i].scan, w.sample.entries()[i].T_world_robot);
  const MapSignature three = MeasureMapSignature({nullptr, &once}, few, {}, {}, options, {});
  EXPECT_FALSE(three.learned);
  EXPECT_EQ(three.scans, 3u);
  EXPECT_DOUBLE_EQ(three.max_expect_value_m, 0.005);
}

}  // namespace
}  // namespace scanloc
