#include "scanloc/simulation/simulated_scan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

// Closed form: the range to the walls of [0, w] × [0, h] from (x, y) along world angle φ.
double RoomRange(double w, double h, double x, double y, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  double r = std::numeric_limits<double>::infinity();
  if (std::abs(c) > 1e-12) r = std::min(r, ((c > 0 ? w : 0.0) - x) / c);
  if (std::abs(s) > 1e-12) r = std::min(r, ((s > 0 ? h : 0.0) - y) / s);
  return r;
}

TEST(SimulateFromLines, CentreOfSquareRoomMatchesClosedForm) {
  const LineMap room = testing::RectangleRoom(4.0, 4.0);
  const ScanLayout layout = MakeLayout(2400, 2.0 * M_PI, 20.0);
  const SimulatedScan sim = SimulateFromLines(room, layout, {2.0, 2.0, 0.0});
  for (std::size_t k = 0; k < layout.beam_count; ++k) {
    const double b = layout.Bearing(k);
    ASSERT_TRUE(sim.IsValid(k)) << "beam " << k;
    EXPECT_NEAR(sim.ranges_m[k], 2.0 / std::max(std::abs(std::cos(b)), std::abs(std::sin(b))), 1e-9)
        << "beam " << k;
    EXPECT_EQ(sim.hit_source[k], HitSource::kSegment);
  }
}

TEST(SimulateFromLines, OffCentreRotatedPostureMatchesClosedForm) {
  const LineMap room = testing::RectangleRoom(6.0, 4.0);
  const ScanLayout layout = MakeLayout(720, 2.0 * M_PI, 20.0);
  const Pose2D pose{1.3, 2.9, 2.7};
  const SimulatedScan sim = SimulateFromLines(room, layout, pose);
  for (std::size_t k = 0; k < layout.beam_count; ++k)
    EXPECT_NEAR(sim.ranges_m[k], RoomRange(6.0, 4.0, 1.3, 2.9, pose.yaw_rad + layout.Bearing(k)),
                1e-9)
        << "beam " << k;
}

TEST(SimulateFromLines, NearerSegmentOccludesTheWallBehind) {
  LineMap map = testing::RectangleRoom(4.0, 4.0);
  map.segments.push_back({{3.0, 1.5}, {3.0, 2.5}});  // a board 1 m ahead of the laser
  const ScanLayout layout = MakeLayout(360, 2.0 * M_PI, 20.0);
  const SimulatedScan sim = SimulateFromLines(map, layout, {2.0, 2.0, 0.0});
  const std::size_t ahead = 180;  // bearing 0
  EXPECT_NEAR(sim.ranges_m[ahead], 1.0, 1e-9);
  EXPECT_EQ(sim.hit_index[ahead], 4);
  // Bearing 20°: passes beside the board (it subtends ±26.6°)? tan(20°) = 0.364 < 0.5 → hits it.
  EXPECT_NEAR(sim.ranges_m[ahead + 20], 1.0 / std::cos(20.0 * M_PI / 180.0), 1e-9);
  // Bearing 30° misses the board and reaches the east wall at x = 4.
  EXPECT_NEAR(sim.ranges_m[ahead + 30], 2.0 / std::cos(30.0 * M_PI / 180.0), 1e-9);
}

TEST(SimulateFromLines, SegmentAcrossTheSeamIsSeenOnBothSides) {
  LineMap map;
  map.segments.push_back({{-1.0, 1.0}, {-1.0, -1.0}});  // behind the laser, across bearing ±π
  const ScanLayout layout = MakeLayout(360, 2.0 * M_PI, 20.0);  // beam 0 at -π
  const SimulatedScan sim = SimulateFromLines(map, layout, {0.0, 0.0, 0.0});
  int hits = 0;
  for (std::size_t k = 0; k < layout.beam_count; ++k) {
    const double b = layout.Bearing(k);
    const bool behind = std::abs(NormalizeAngle(b - M_PI)) <= M_PI / 4 + 1e-9;
    EXPECT_EQ(sim.IsValid(k), behind) << "beam " << k;
    if (behind) {
      EXPECT_NEAR(sim.ranges_m[k], 1.0 / std::abs(std::cos(b)), 1e-9);
      ++hits;
    }
  }
  EXPECT_EQ(hits, 91);  // -135°..-180° and 135°..179°: 46 + 45 beams
}

TEST(SimulateFromLines, SeamCrossingWorksWhenTheLaserIsRotated) {
  LineMap map;
  map.segments.push_back({{1.0, -0.5}, {1.0, 0.5}});  // ahead in the world
  const ScanLayout layout = MakeLayout(360, 2.0 * M_PI, 20.0);
  const SimulatedScan sim = SimulateFromLines(map, layout, {0.0, 0.0, M_PI});  // facing away
  EXPECT_NEAR(sim.ranges_m[0], 1.0, 1e-9);  // beam 0 at -π in the laser frame points to +x
  EXPECT_TRUE(sim.IsValid(359));
}

TEST(SimulateFromLines, EdgeOnSegmentReturnsItsNearerVertex) {
  LineMap map;
  map.segments.push_back({{2.0, 0.0}, {1.0, 0.0}});  // along the beam at bearing 0
  const ScanLayout layout = MakeLayout(361, M_PI, 20.0);
  const SimulatedScan sim = SimulateFromLines(map, layout, {0.0, 0.0, 0.0});
  EXPECT_NEAR(sim.ranges_m[180], 1.0, 1e-9);
  int hits = 0;
  for (std::size_t k = 0; k < layout.beam_count; ++k) hits += sim.IsValid(k);
  EXPECT_EQ(hits, 1);
}

TEST(SimulateFromLines, SegmentPartlyOutsideTheAngularLimitsFillsOnlyBeamsInside) {
  LineMap map;
  map.segments.push_back({{-1.0, 1.0}, {1.0, 1.0}});      // spans bearings 45°..135°
  const ScanLayout layout = MakeLayout(181, M_PI, 20.0);  // -90°..90°, 1° steps
  const SimulatedScan sim = SimulateFromLines(map, layout, {0.0, 0.0, 0.0});
  for (std::size_t k = 0; k < layout.beam_count; ++k) {
    const double deg = -90.0 + k;
    EXPECT_EQ(sim.IsValid(k), deg >= 45.0 - 1e-9) << deg;
    if (sim.IsValid(k)) {
      EXPECT_NEAR(sim.ranges_m[k], 1.0 / std::sin(deg * M_PI / 180.0), 1e-9);
    }
  }
}

TEST(SimulateFromLines, HitsBeyondMaximumRangeAreNoReturn) {
  const LineMap room = testing::RectangleRoom(40.0, 40.0);
  const ScanLayout layout = MakeLayout(360, 2.0 * M_PI, 20.0);
  const SimulatedScan sim = SimulateFromLines(room, layout, {5.0, 20.0, 0.0});
  EXPECT_NEAR(sim.ranges_m[0], 5.0, 1e-9);                        // west wall, bearing -π
  EXPECT_FALSE(sim.IsValid(180));                                 // east wall 35 m away
  EXPECT_DOUBLE_EQ(sim.ranges_m[180], SimulatedScan::kNoReturn);  // the trials' -1.0
}

TEST(SimulateFromPoints, SampledLineMapAgreesWithTheLineMap) {
  LineMap map = testing::RectangleRoom(6.0, 5.0);
  map.segments.push_back({{4.0, 3.5}, {5.0, 3.5}});
  const PointMap points = PointMapFromLines(map, 0.0075, {0.0, 0.3});
  const ScanLayout layout = MakeLayout(2400, 2.0 * M_PI, 20.0);
  const Pose2D pose{2.2, 1.9, 0.4};
  const SimulatedScan from_lines = SimulateFromLines(map, layout, pose);
  const SimulatedScan from_points = SimulateFromPoints(points, layout, pose);
  std::vector<double> errors;
  for (std::size_t k = 0; k < layout.beam_count; ++k) {
    ASSERT_EQ(from_lines.IsValid(k), from_points.IsValid(k)) << "beam " << k;
    errors.push_back(std::abs(from_lines.ranges_m[k] - from_points.ranges_m[k]));
  }
  std::sort(errors.begin(), errors.end());
  // Points 7.5 mm apart seen at up to ~4 m: the nearest sample lies within a few millimetres of
  // the beam's hit, except at grazing incidence and behind the board's ends.
  EXPECT_LT(errors[errors.size() / 2], 0.005);
  EXPECT_LT(errors[errors.size() * 95 / 100], 0.02);
}

TEST(SimulateFromPoints, SparseNearPointsOccludeDenseFarPoints) {
  PointMap map(PointMapOptions{0.0, 1.0});
  // A near wall at x = 2 sampled every 0.2 m, a far wall at x = 6 sampled every 1 cm.
  for (double y = -1.0; y <= 1.0 + 1e-9; y += 0.2) map.Insert({2.0, y}, 0.2);
  for (double y = -4.0; y <= 4.0 + 1e-9; y += 0.01) map.Insert({6.0, y}, 0.01);
  const ScanLayout layout = MakeLayout(2400, 2.0 * M_PI, 20.0);
  const Pose2D pose{0.0, 0.0, 0.0};
  auto count_far_within_near_wall = [&](const SimulatedScan& sim) {
    int far = 0;
    for (std::size_t k = 0; k < layout.beam_count; ++k) {
      const double b = layout.Bearing(k);
      if (std::abs(b) < std::atan(0.9 / 2.0) && sim.IsValid(k) && sim.ranges_m[k] > 3.0) ++far;
    }
    return far;
  };
  const SimulatedScan chapter = SimulateFromPoints(map, layout, pose, {0.0});
  const SimulatedScan occluding = SimulateFromPoints(map, layout, pose);
  EXPECT_GT(count_far_within_near_wall(chapter), 100);  // (3.7) lets the far wall show through
  EXPECT_EQ(count_far_within_near_wall(occluding), 0);
}

TEST(SimulateFromPoints, SurfelsGiveTheWallRangeBetweenSparsePoints) {
  // A wall at x = 3 sampled every 0.2 m, seen obliquely with 1° beams: a point taken as a disc is
  // off by up to spacing·tan(incidence), a surfel (point + normal) is exact.
  PointMap discs(PointMapOptions{0.0, 1.0}), surfels(PointMapOptions{0.0, 1.0});
  for (double y = 0.0; y <= 6.0 + 1e-9; y += 0.2) {
    discs.Insert(std::vector<Eigen::Vector2d>{{3.0, y}}, {0.2});
    surfels.Insert(std::vector<Eigen::Vector2d>{{3.0, y}}, {0.2},
                   std::vector<Eigen::Vector2d>{{-1.0, 0.0}});
  }
  const ScanLayout layout = MakeLayout(181, M_PI, 20.0);
  const Pose2D pose{0.0, 0.0, 0.0};
  const SimulatedScan from_discs = SimulateFromPoints(discs, layout, pose);
  const SimulatedScan from_surfels = SimulateFromPoints(surfels, layout, pose);
  double worst_disc = 0.0;
  for (int deg = 20; deg <= 60; ++deg) {
    const std::size_t k = 90 + deg;
    const double truth = 3.0 / std::cos(deg * M_PI / 180.0);
    ASSERT_TRUE(from_surfels.IsValid(k)) << deg;
    EXPECT_NEAR(from_surfels.ranges_m[k], truth, 1e-9) << deg;
    worst_disc = std::max(worst_disc, std::abs(from_discs.ranges_m[k] - truth));
  }
  EXPECT_GT(worst_disc, 0.05);  // the discs' error this test guards against
}

TEST(SimulateFromPoints, SurfelsFromAScanReproduceTheScannedWall) {
  // A point map grown from one scan of a room, simulated again from the same posture, gives the
  // scan back (the normals come from the neighbouring beams).
  const LineMap room = testing::RectangleRoom(8.0, 5.0);
  const ScanLayout layout = MakeLayout(180, M_PI, 20.0);
  const Pose2D pose{2.0, 1.5, 0.6};
  const LaserScan scan = testing::ScanFromSimulation(SimulateFromLines(room, layout, pose));
  PointMap map(PointMapOptions{0.0, 0.3});
  map.InsertScan(scan, pose);
  const SimulatedScan again = SimulateFromPoints(map, layout, pose);
  int close = 0, valid = 0;
  for (std::size_t k = 0; k < layout.beam_count; ++k) {
    if (!scan.IsValid(k)) continue;
    ++valid;
    close += again.IsValid(k) && std::abs(again.ranges_m[k] - scan.ranges_m[k]) < 1e-6;
  }
  EXPECT_GE(close, valid - 4);  // only the beams at the two corners may differ
}

TEST(SimulateFromPoints, IndexedEqualsBruteForceOnRandomMapsOfDiscsAndSurfels) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> coordinate(-30.0, 30.0), yaw(-M_PI, M_PI);
  const ScanLayout layout = MakeLayout(1000, 2.0 * M_PI, 20.0);
  for (const int size : {1, 100, 5000, 50000}) {
    PointMap map(PointMapOptions{0.0, 0.3});
    std::vector<Eigen::Vector2d> points, normals;
    for (int i = 0; i < size; ++i) {
      points.emplace_back(coordinate(rng), coordinate(rng));
      const double a = yaw(rng);  // every other point a surfel, the others discs
      normals.push_back(i % 2 ? Eigen::Vector2d(std::cos(a), std::sin(a))
                              : Eigen::Vector2d::Zero());
    }
    map.Insert(points, std::vector<double>(points.size(), 0.05), normals);
    for (int trial = 0; trial < 5; ++trial) {
      const Pose2D pose{coordinate(rng) / 2, coordinate(rng) / 2, yaw(rng)};
      const SimulatedScan a = SimulateFromPoints(map, layout, pose);
      const SimulatedScan b = SimulateFromPointsBruteForce(map, layout, pose);
      for (std::size_t k = 0; k < layout.beam_count; ++k) {
        ASSERT_EQ(a.IsValid(k), b.IsValid(k)) << "size " << size << " beam " << k;
        if (a.IsValid(k)) {
          ASSERT_DOUBLE_EQ(a.ranges_m[k], b.ranges_m[k]);
          ASSERT_EQ(a.hit_index[k], b.hit_index[k]) << "size " << size << " beam " << k;
        }
      }
    }
  }
}

// The ring building with a 2 m doorway in each outer wall and a far wall 30 m beyond the east
// door: beams leave through the doors, so the block walk must search past the building.
LineMap BuildingWithDoors() {
  LineMap map = testing::RingBuilding();
  LineMap doors;
  for (const Segment& segment : map.segments) {
    const bool outer = segment.Length() >= 16.0;
    if (!outer) {
      doors.segments.push_back(segment);
      continue;
    }
    const Eigen::Vector2d mid = 0.5 * (segment.a + segment.b);
    const Eigen::Vector2d along = (segment.b - segment.a).normalized();
    doors.segments.push_back({segment.a, mid - along});
    doors.segments.push_back({mid + along, segment.b});
  }
  doors.segments.push_back({{54.0, -10.0}, {54.0, 26.0}});
  return doors;
}

// A map grown as a session grows it: noisy scans merged into cell means (which move off their
// first samples), clutter that later scans carve away (dead slots).
PointMap GrownMap(const LineMap& building, std::mt19937& rng) {
  PointMap map;  // the default cell size: samples merge
  std::uniform_real_distribution<double> x(1.0, 23.0), y(1.0, 3.0), yaw(-M_PI, M_PI);
  std::vector<Pose2D> poses;
  for (int i = 0; i < 12; ++i) poses.emplace_back(x(rng), i % 2 ? y(rng) : 16.0 - y(rng), yaw(rng));
  for (std::size_t i = 0; i < poses.size(); ++i)
    map.InsertScan(testing::NoisyScan(building, poses[i], 720, 0.02, 100 + i), poses[i]);
  std::vector<Eigen::Vector2d> clutter;
  for (int i = 0; i < 300; ++i) clutter.emplace_back(x(rng), y(rng));
  map.Insert(clutter, std::vector<double>(clutter.size(), 0.05));
  for (int pass = 0; pass < 3; ++pass)
    for (std::size_t i = 0; i < poses.size(); ++i)
      map.CarveFreeSpace(testing::NoisyScan(building, poses[i], 720, 0.0, 0), poses[i], 0.2, 0.0);
  return map;
}

TEST(SimulateFromPoints, BlockWalkEqualsBruteForceOnAGrownMapWithDoorsToTheLastTie) {
  std::mt19937 rng(77);
  const PointMap map = GrownMap(BuildingWithDoors(), rng);
  ASSERT_LT(map.live_size(), map.size());  // carving removed clutter: dead slots are skipped
  std::uniform_real_distribution<double> x(-20.0, 70.0), y(-20.0, 36.0), yaw(-M_PI, M_PI);
  int open_beams = 0, hits = 0;
  for (const double range_max_m : {5.0, 20.0, 80.0})
    for (const double footprint : {0.0, 1.0, 4.0})
      for (int trial = 0; trial < 6; ++trial) {
        const ScanLayout layout =
            MakeLayout(trial % 2 ? 181 : 1081, trial % 3 ? M_PI : 2 * M_PI, range_max_m);
        const Pose2D pose = trial < 4 ? Pose2D{x(rng) / 4.0 + 12.0, y(rng) / 8.0 + 2.0, yaw(rng)}
                                      : Pose2D{x(rng), y(rng), yaw(rng)};
        const PointSimulationOptions options{footprint};
        const SimulatedScan a = SimulateFromPoints(map, layout, pose, options);
        const SimulatedScan b = SimulateFromPointsBruteForce(map, layout, pose, options);
        for (std::size_t k = 0; k < layout.beam_count; ++k) {
          ASSERT_EQ(a.IsValid(k), b.IsValid(k)) << range_max_m << " m, beam " << k;
          open_beams += !a.IsValid(k);
          if (!a.IsValid(k)) continue;
          ++hits;
          ASSERT_EQ(a.ranges_m[k], b.ranges_m[k]) << range_max_m << " m, beam " << k;
          ASSERT_EQ(a.hit_index[k], b.hit_index[k]) << range_max_m << " m, beam " << k;
        }
      }
  // Both kinds of beam were exercised: the doors and the short ranges leave many open.
  EXPECT_GT(open_beams, 5000);
  EXPECT_GT(hits, 5000);
}

TEST(SimulateFromPoints, EqualRangesKeepTheLowerIndexWhateverBlockIsVisitedFirst) {
  // Two discs at the same range (exactly: mirrored dyadic offsets), with footprints so wide that
  // both cover the beams between them. Point 1 lies in a nearer ring of blocks than point 0, so
  // it is offered first; the brute force, in index order, keeps point 0.
  PointMap map(PointMapOptions{0.0, 0.3});
  map.Restore({{4.75, 1.5}, {2.5, 3.75}}, {0.3, 0.3});
  const Pose2D pose{1.5, 0.5, 0.0};  // offsets (3.25, 1.0) and (1.0, 3.25)
  const ScanLayout layout = MakeLayout(360, 2.0 * M_PI, 20.0);
  const PointSimulationOptions wide{40.0};
  const SimulatedScan a = SimulateFromPoints(map, layout, pose, wide);
  const SimulatedScan b = SimulateFromPointsBruteForce(map, layout, pose, wide);
  const std::size_t between = 180 + 45;  // bearing 45°, midway
  ASSERT_TRUE(b.IsValid(between));
  EXPECT_EQ(b.hit_index[between], 0);
  EXPECT_EQ(a.hit_index, b.hit_index);
  EXPECT_EQ(a.ranges_m, b.ranges_m);
}

TEST(SimulateFromPoints, FarFromTheMapEveryBeamIsOpenAndHugeCoordinatesStillWork) {
  PointMap map;
  map.Insert(std::vector<Eigen::Vector2d>{{0.0, 0.0}, {1e12, 0.0}}, {0.05, 0.05});
  const ScanLayout layout = MakeLayout(360, 2.0 * M_PI, 20.0);
  const SimulatedScan far = SimulateFromPoints(map, layout, {500.0, 500.0, 0.0});
  EXPECT_EQ(std::count(far.hit_source.begin(), far.hit_source.end(), HitSource::kNone), 360);
  const SimulatedScan near_huge = SimulateFromPoints(map, layout, {1e12 - 3.0, 0.0, 0.0});
  EXPECT_NEAR(near_huge.ranges_m[180], 3.0, 1e-3);  // the point 3 m ahead (bearing 0: beam 180)
}

TEST(Simulate, BothMapsKeepTheNearerHitPerBeam) {
  const LineMap room = testing::RectangleRoom(4.0, 4.0);
  PointMap points(PointMapOptions{0.0, 0.3});
  points.Insert({3.0, 2.0}, 0.05);  // a post 1 m ahead, not in the line map
  const ScanLayout layout = MakeLayout(360, 2.0 * M_PI, 20.0);
  const SimulatedScan sim = Simulate(MapView{&room, &points}, layout, {2.0, 2.0, 0.0});
  EXPECT_NEAR(sim.ranges_m[180], 1.0, 1e-9);
  EXPECT_EQ(sim.hit_source[180], HitSource::kPoint);
  EXPECT_NEAR(sim.ranges_m[0], 2.0, 1e-9);
  EXPECT_EQ(sim.hit_source[0], HitSource::kSegment);
  const SimulatedScan nothing = Simulate(MapView{}, layout, {2.0, 2.0, 0.0});
  EXPECT_EQ(std::count(nothing.hit_source.begin(), nothing.hit_source.end(), HitSource::kNone),
            360);
}

}  // namespace
}  // namespace scanloc
