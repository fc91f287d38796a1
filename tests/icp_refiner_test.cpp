#include "scanloc/refinement/icp_refiner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

constexpr double kNoiseSigmaM = 0.02;  // the Acuity's range error

using testing::RealScan;

std::string Report(const RefinementResult& r) {
  std::ostringstream os;
  os << "pose " << r.T_world_laser << " converged " << r.converged << " iterations " << r.iterations
     << " EV " << r.test_before.expect_value_m << " -> " << r.test_after.expect_value_m << " MP "
     << r.test_before.match_pairs << " -> " << r.test_after.match_pairs << "/"
     << r.test_after.valid_pairs << " time " << r.time_s << " s";
  return os.str();
}

const Pose2D kTrue(3.2, 2.5, 0.3);
const Pose2D kOffsets[] = {Pose2D(0.0317, -0.0213, 0.0191), Pose2D(-0.0388, 0.0291, -0.0147),
                           Pose2D(0.0523, 0.0109, 0.0213), Pose2D(-0.0196, -0.0481, -0.0202)};

Pose2D Offset(const Pose2D& offset) {
  return Pose2D(kTrue.x_m + offset.x_m, kTrue.y_m + offset.y_m, kTrue.yaw_rad + offset.yaw_rad);
}

void ExpectNearTrue(const RefinementResult& r, double tolerance_m, double tolerance_rad) {
  EXPECT_NEAR(r.T_world_laser.x_m, kTrue.x_m, tolerance_m);
  EXPECT_NEAR(r.T_world_laser.y_m, kTrue.y_m, tolerance_m);
  EXPECT_NEAR(r.T_world_laser.yaw_rad, kTrue.yaw_rad, tolerance_rad);
}

TEST(IcpRefiner, PointToPointRecoversTruePoseWithinTwoMillimetresNoiseFree) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  for (const Pose2D& offset : kOffsets) {
    const RefinementResult r =
        RefineIcp(MapView{&lines, nullptr}, scan, Offset(offset), ScoringOptions{});
    SCOPED_TRACE(Report(r));
    EXPECT_TRUE(r.converged);
    EXPECT_GT(r.iterations, 0);
    // Nearest sampled map point instead of the wall: observed ≤ 0.7 mm / 0.65 mrad.
    ExpectNearTrue(r, 0.002, 0.0015);
    EXPECT_LE(r.test_after.expect_value_m, r.test_before.expect_value_m);
  }
}

TEST(IcpRefiner, PointToLineRecoversTruePoseWithinATenthOfAMillimetreNoiseFree) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  IcpOptions options;
  options.point_to_plane = true;
  for (const Pose2D& offset : kOffsets) {
    const RefinementResult r =
        RefineIcp(MapView{&lines, nullptr}, scan, Offset(offset), ScoringOptions{}, options);
    SCOPED_TRACE(Report(r));
    EXPECT_TRUE(r.converged);
    // Point-to-line slides along the walls: only float rounding remains (observed 5 µm).
    ExpectNearTrue(r, 1e-4, 5e-5);
    EXPECT_LE(r.test_after.expect_value_m, r.test_before.expect_value_m);
  }
}

TEST(IcpRefiner, ExpectValueNeverIncreasesAndPoseStaysWithinFiveMillimetresWithRangeNoise) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, kNoiseSigmaM);
  for (const bool point_to_plane : {false, true}) {
    IcpOptions options;
    options.point_to_plane = point_to_plane;
    const RefinementResult r =
        RefineIcp(MapView{&lines, nullptr}, scan, Offset(kOffsets[1]), ScoringOptions{}, options);
    SCOPED_TRACE(std::string(point_to_plane ? "point-to-line: " : "point-to-point: ") + Report(r));
    EXPECT_TRUE(r.converged);
    EXPECT_LE(r.test_after.expect_value_m, r.test_before.expect_value_m);
    ExpectNearTrue(r, 0.005, 0.002);  // observed ≤ 0.9 mm / 0.8 mrad
  }
}

TEST(IcpRefiner, RecoversTruePoseWithinTwoMillimetresOnPointMapAndOnLinesPlusPoints) {
  const LineMap lines = testing::SmallRoomWithL();
  const PointMap points = PointMapFromLines(lines);
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  for (const MapView& map : {MapView{nullptr, &points}, MapView{&lines, &points}}) {
    for (const bool point_to_plane : {false, true}) {
      IcpOptions options;
      options.point_to_plane = point_to_plane;
      const RefinementResult r =
          RefineIcp(map, scan, Offset(kOffsets[0]), ScoringOptions{}, options);
      SCOPED_TRACE(std::string(map.lines ? "lines+points, " : "points, ") +
                   (point_to_plane ? "point-to-line: " : "point-to-point: ") + Report(r));
      EXPECT_TRUE(r.converged);
      ExpectNearTrue(r, 0.002, 0.0015);  // observed ≤ 0.7 mm / 0.65 mrad
    }
  }
}

TEST(IcpRefiner, EmptyMapGivesInitialPoseNotConverged) {
  const LineMap lines = testing::SmallRoomWithL();
  const LineMap empty_lines;
  const PointMap empty_points;
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  for (const MapView& map :
       {MapView{}, MapView{&empty_lines, nullptr}, MapView{&empty_lines, &empty_points}}) {
    const RefinementResult r = RefineIcp(map, scan, Offset(kOffsets[0]), ScoringOptions{});
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(r.iterations, 0);
    EXPECT_DOUBLE_EQ(r.T_world_laser.x_m, Offset(kOffsets[0]).x_m);
    EXPECT_EQ(r.test_after.valid_pairs, 0);
  }
}

TEST(IcpRefiner, AllInvalidScanGivesInitialPoseNotConverged) {
  const LineMap lines = testing::SmallRoomWithL();
  LaserScan scan = RealScan(lines, kTrue, 0.0);
  for (double& range : scan.ranges_m) range = -1.0;
  for (const bool point_to_plane : {false, true}) {
    IcpOptions options;
    options.point_to_plane = point_to_plane;
    const RefinementResult r =
        RefineIcp(MapView{&lines, nullptr}, scan, Offset(kOffsets[0]), ScoringOptions{}, options);
    EXPECT_FALSE(r.converged);
    EXPECT_DOUBLE_EQ(r.T_world_laser.yaw_rad, Offset(kOffsets[0]).yaw_rad);
    EXPECT_EQ(r.test_after.valid_pairs, 0);
  }
}

TEST(IcpRefiner, MapOutOfRangeGivesInitialPoseNotConverged) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  // 100 m away: no map point lies within the scan's 20 m range_max.
  const Pose2D far_away(100.0, 100.0, 0.0);
  const RefinementResult r = RefineIcp(MapView{&lines, nullptr}, scan, far_away, ScoringOptions{});
  EXPECT_FALSE(r.converged);
  EXPECT_DOUBLE_EQ(r.T_world_laser.x_m, far_away.x_m);
}

TEST(IcpRefiner, IterationCapReachedIsReportedAsNotConverged) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  IcpOptions options;
  options.max_iterations = 1;
  const RefinementResult r =
      RefineIcp(MapView{&lines, nullptr}, scan, Offset(kOffsets[2]), ScoringOptions{}, options);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 1);
}

TEST(IcpRefiner, InvalidOptionsThrowWithMessage) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  const MapView map{&lines, nullptr};
  auto expect_throw = [&](IcpOptions options, const std::string& field) {
    try {
      RefineIcp(map, scan, kTrue, ScoringOptions{}, options);
      ADD_FAILURE() << "no exception for " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  IcpOptions o;
  o.max_correspondence_distance_m = 0.0;
  expect_throw(o, "max_correspondence_distance_m");
  o = {};
  o.max_iterations = 0;
  expect_throw(o, "max_iterations");
  o = {};
  o.transformation_epsilon = -1.0;
  expect_throw(o, "transformation_epsilon");
  o = {};
  o.euclidean_fitness_epsilon = std::nan("");
  expect_throw(o, "euclidean_fitness_epsilon");
  EXPECT_THROW(RefineIcp(map, scan, Pose2D(0, std::nan(""), 0), ScoringOptions{}),
               std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
