// Free-space carving of the point map: what a scan saw through leaves the map, what it saw stays.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/maps/point_map_io.hpp"
#include "scanloc/simulation/simulated_scan.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

// A 10 m × 8 m room seen from its centre with 720 beams over 360°, no noise.
class CarvingTest : public ::testing::Test {
 protected:
  LineMap room_ = testing::RectangleRoom(10.0, 8.0);
  Pose2D centre_{5.0, 4.0, 0.0};
  LaserScan scan_ = testing::NoisyScan(room_, centre_, 720, 0.0, 1);
  PointMap map_;
  // A fixed margin without growth with the range: the cases below are laid out for it.
  static constexpr double kMargin = 0.2, kMarginPerM = 0.0;
};

TEST_F(CarvingTest, APointSeenThroughTwiceMoreThanSeenIsRemoved) {
  map_.InsertScan(scan_, centre_);
  const std::size_t walls = map_.live_size();
  // A person who stood 2 m east of the robot once: one sample.
  ASSERT_TRUE(map_.Insert(Eigen::Vector2d(7.0, 4.0), 0.05));
  EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM),
            0u);  // one miss, one sample: kept
  EXPECT_EQ(map_.live_size(), walls + 1);
  EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM), 1u);  // two misses: removed
  EXPECT_EQ(map_.live_size(), walls);
  EXPECT_EQ(map_.size(), walls + 1);  // its slot stays, dead
  EXPECT_FALSE(map_.alive(walls));
  // Searches no longer see it, the walls are all there.
  EXPECT_TRUE(map_.RadiusSearch({7.0, 4.0}, 0.5).empty());
  // A radius that covers the whole map lists the live points without the tree: not this one.
  const auto everything = map_.RadiusSearch({7.0, 4.0}, 100.0);
  EXPECT_EQ(everything.size(), walls);
  for (const auto& [index, squared_distance] : everything) EXPECT_NE(index, walls);
  const auto nearest = map_.KNearest({7.0, 4.0}, 1);
  ASSERT_EQ(nearest.size(), 1u);
  EXPECT_NEAR(std::sqrt(nearest[0].second), 3.0, 0.05);  // the east wall at x = 10
}

TEST_F(CarvingTest, WallsAndPointsNearTheReturnAreNeverCarved) {
  map_.InsertScan(scan_, centre_);
  map_.Insert(Eigen::Vector2d(9.9, 4.0), 0.05);  // 0.1 m in front of the east wall: within margin
  const std::size_t before = map_.live_size();
  for (int i = 0; i < 5; ++i) EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, 0.2, 0.0), 0u);
  EXPECT_EQ(map_.live_size(), before);
}

TEST_F(CarvingTest, TheMarginGrowsWithTheRangeOfTheReturn) {
  map_.InsertScan(scan_, centre_);
  // 0.18 m in front of the east wall, whose return is 5 m away: seen through with 0.1 m + 1 % of
  // the return (0.15 m), not with a fixed 0.2 m nor with 0.1 m + 5 % (0.35 m).
  ASSERT_TRUE(map_.Insert(Eigen::Vector2d(9.82, 4.0), 0.05));
  const std::size_t with_point = map_.live_size();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, 0.2, 0.0), 0u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, 0.1, 0.05), 0u);
  EXPECT_EQ(map_.live_size(), with_point);
  EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, 0.1, 0.01), 0u);  // one miss, one sample
  EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, 0.1, 0.01), 1u);  // two misses: removed
  EXPECT_EQ(map_.live_size(), with_point - 1);
  EXPECT_THROW(map_.CarveFreeSpace(scan_, centre_, 0.1, 1.0), std::invalid_argument);
  EXPECT_THROW(map_.CarveFreeSpace(scan_, centre_, 0.1, -0.01), std::invalid_argument);
}

TEST_F(CarvingTest, ACarvedCellTakesNewSamplesAsANewPoint) {
  map_.InsertScan(scan_, centre_);
  map_.Insert(Eigen::Vector2d(7.0, 4.0), 0.05);
  map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM);
  map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM);
  const std::size_t live = map_.live_size();
  // Something is there again: it must come back rather than merge into the dead point.
  EXPECT_TRUE(map_.Insert(Eigen::Vector2d(7.01, 4.0), 0.05));
  EXPECT_EQ(map_.live_size(), live + 1);
  EXPECT_EQ(map_.RadiusSearch({7.0, 4.0}, 0.1).size(), 1u);
}

TEST_F(CarvingTest, BeamsWithoutEchoCarveNothing) {
  map_.Insert(Eigen::Vector2d(7.0, 4.0), 0.05);
  LaserScan blind = scan_;
  for (double& r : blind.ranges_m) r = -1.0;
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(map_.CarveFreeSpace(blind, centre_, kMargin, kMarginPerM), 0u);
  EXPECT_EQ(map_.live_size(), 1u);
}

TEST_F(CarvingTest, PointsBesideADepthJumpAreKept) {
  // A pillar 2 m east hides part of the east wall; wall points just beside the shadow's edge lie
  // behind the pillar's neighbouring beam and must not be carved by the beam next to it.
  LineMap world = room_;
  world.segments.push_back({{6.9, 3.9}, {6.9, 4.1}});
  const LaserScan with_pillar = testing::NoisyScan(world, centre_, 720, 0.0, 1);
  map_.InsertScan(scan_, centre_);  // the wall seen before the pillar was there
  const std::size_t before = map_.live_size();
  for (int i = 0; i < 3; ++i) map_.CarveFreeSpace(with_pillar, centre_, kMargin, kMarginPerM);
  EXPECT_EQ(map_.live_size(), before);  // the pillar is in front of them, nothing seen through
}

TEST_F(CarvingTest, SavedMapsHoldOnlyLivePoints) {
  map_.InsertScan(scan_, centre_);
  map_.Insert(Eigen::Vector2d(7.0, 4.0), 0.05);
  map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM);
  map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM);
  const std::string path = testing::TemporaryDir() + "/carved.pcd";
  SavePointMapPcd(map_, path);
  const PointMap loaded = LoadPointMapPcd(path);
  EXPECT_EQ(loaded.live_size(), map_.live_size());
  EXPECT_TRUE(loaded.RadiusSearch({7.0, 4.0}, 0.5).empty());
}

// The carving rule point by point, over every live point: the oracle for the carving's culling
// of whole blocks. Returns the points the scan saw through (their misses grow by one).
std::vector<std::size_t> SeenThrough(const PointMap& map, const LaserScan& scan,
                                     const Pose2D& T_world_laser, double margin_m,
                                     double margin_per_m) {
  const std::size_t n = scan.size();
  double reach_m = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    if (scan.IsValid(k)) reach_m = std::max(reach_m, scan.ranges_m[k]);
  std::vector<std::size_t> seen;
  const double inc = scan.layout.angle_increment_rad;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (!map.alive(i)) continue;
    const Eigen::Vector2d q = T_world_laser.Inverse().Transform(map.point(i));
    const double range = q.norm();
    if (!(range < reach_m) || range <= scan.layout.range_min_m) continue;
    const double beam = std::round(
        NormalizeAngle(std::atan2(q.y(), q.x()) - scan.layout.angle_min_rad - 0.5 * (n - 1) * inc) /
            inc +
        0.5 * (n - 1));
    if (!(beam >= 1.0) || beam > static_cast<double>(n - 2)) continue;
    const auto k = static_cast<std::size_t>(beam);
    if (!scan.IsValid(k - 1) || !scan.IsValid(k) || !scan.IsValid(k + 1)) continue;
    const double hit = std::min({scan.ranges_m[k - 1], scan.ranges_m[k], scan.ranges_m[k + 1]});
    if (range < hit - margin_m - margin_per_m * hit) seen.push_back(i);
  }
  return seen;
}

// 20,000 points over a 60 m square around the ring building, one sample each, no merging.
PointMap ClutterMap(std::mt19937& rng) {
  std::uniform_real_distribution<double> coordinate(-18.0, 42.0);
  std::vector<Eigen::Vector2d> clutter;
  for (int i = 0; i < 20000; ++i) clutter.emplace_back(coordinate(rng), coordinate(rng) - 10.0);
  PointMap map(PointMapOptions{0.0, 0.3});
  map.Insert(clutter, std::vector<double>(clutter.size(), 0.05));
  return map;
}

TEST(CarvingOracleTest, BlockCullingRemovesExactlyThePointsTheRuleRemovesPointByPoint) {
  // Clutter over a 60 m square (one sample each, so a point goes at its second miss) carved by
  // scans of the ring building from random postures inside and outside it, half and full circle,
  // short and long range.
  LineMap building = testing::RingBuilding();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coordinate(-18.0, 42.0), yaw(-M_PI, M_PI);
  PointMap map = ClutterMap(rng);
  std::vector<int> misses(map.size(), 0);
  std::size_t removed_total = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const Pose2D pose{coordinate(rng) / 3.0 + 6.0, coordinate(rng) / 4.0 + 2.0, yaw(rng)};
    LaserScan scan = testing::NoisyScan(building, pose, trial % 2 ? 361 : 720, 0.01, trial);
    scan.layout.range_max_m = trial % 3 ? 30.0 : 6.0;  // short: many beams without echo
    for (double& r : scan.ranges_m)
      if (!(r < scan.layout.range_max_m)) r = scan.layout.range_max_m;
    // Each scan twice: a point it saw through is then removed, so `alive` shows every miss.
    for (int again = 0; again < 2; ++again) {
      for (const std::size_t i : SeenThrough(map, scan, pose, 0.1, 0.01)) ++misses[i];
      removed_total += map.CarveFreeSpace(scan, pose, 0.1, 0.01);
    }
    for (std::size_t i = 0; i < map.size(); ++i)
      ASSERT_EQ(map.alive(i), misses[i] < 2) << "trial " << trial << " point " << i;
  }
  EXPECT_GT(removed_total, 1000u);  // the rule had work to do (1,233 when written)
  EXPECT_LT(removed_total, 19000u);
}

// Carved points leave the lists that radius searches and the simulated scans' block walk read:
// after each carving, both still see exactly the live points, as a pass over every point does.
TEST(CarvingOracleTest, SearchesAndSimulatedScansOfACarvedMapSeeExactlyItsLivePoints) {
  LineMap building = testing::RingBuilding();
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> coordinate(-18.0, 42.0), yaw(-M_PI, M_PI);
  PointMap map = ClutterMap(rng);
  std::size_t removed_total = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const Pose2D pose{coordinate(rng) / 3.0 + 6.0, coordinate(rng) / 4.0 + 2.0, yaw(rng)};
    const LaserScan scan = testing::NoisyScan(building, pose, 720, 0.01, trial);
    for (int again = 0; again < 2; ++again)
      removed_total += map.CarveFreeSpace(scan, pose, 0.1, 0.01);
    // Radii for the search cells (0.3, 0.7 m), the tree (3 m) and the whole map (100 m).
    for (const double radius : {0.3, 0.7, 3.0, 100.0})
      for (int query = 0; query < 5; ++query) {
        const Eigen::Vector2d centre(coordinate(rng), coordinate(rng) - 10.0);
        std::vector<std::pair<std::uint32_t, double>> expected;
        for (std::size_t i = 0; i < map.size(); ++i) {
          const double d2 = (map.point(i) - centre).squaredNorm();
          if (map.alive(i) && d2 < radius * radius)
            expected.emplace_back(static_cast<std::uint32_t>(i), d2);
        }
        auto found = map.RadiusSearch(centre, radius);
        std::sort(found.begin(), found.end());
        ASSERT_EQ(found, expected) << "trial " << trial << " radius " << radius;
      }
    for (const Pose2D& at : {pose, Pose2D{coordinate(rng) / 2.0, coordinate(rng) / 2.0, 0.3}}) {
      const SimulatedScan walked = SimulateFromPoints(map, scan.layout, at);
      const SimulatedScan every = SimulateFromPointsBruteForce(map, scan.layout, at);
      for (std::size_t k = 0; k < scan.size(); ++k) {
        ASSERT_EQ(walked.IsValid(k), every.IsValid(k)) << "trial " << trial << " beam " << k;
        if (!walked.IsValid(k)) continue;
        ASSERT_EQ(walked.ranges_m[k], every.ranges_m[k]) << "trial " << trial << " beam " << k;
        ASSERT_EQ(walked.hit_index[k], every.hit_index[k]) << "trial " << trial << " beam " << k;
      }
    }
  }
  EXPECT_GT(removed_total, 500u);  // carving had work to do
}

TEST_F(CarvingTest, NegativeMarginIsRefused) {
  EXPECT_THROW(map_.CarveFreeSpace(scan_, centre_, -0.1, 0.0), std::invalid_argument);
}

TEST_F(CarvingTest, PointsBelowTheFirstIndexAreLeftAsTheyAre) {
  map_.InsertScan(scan_, centre_);
  const std::size_t walls = map_.live_size();
  ASSERT_TRUE(map_.Insert(Eigen::Vector2d(7.0, 4.0), 0.05));  // index `walls`
  const auto after_it = static_cast<std::uint32_t>(walls + 1);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM, after_it), 0u);
  EXPECT_EQ(map_.live_size(), walls + 1);  // no miss counted either: two more remove it
  const auto from_it = static_cast<std::uint32_t>(walls);
  EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM, from_it), 0u);
  EXPECT_EQ(map_.CarveFreeSpace(scan_, centre_, kMargin, kMarginPerM, from_it), 1u);
  EXPECT_FALSE(map_.alive(walls));
}

}  // namespace
}  // namespace scanloc
