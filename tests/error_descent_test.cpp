#include "scanloc/refinement/error_descent.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

constexpr double kNoiseSigmaM = 0.02;  // the Acuity's range error
// (3.11) α, the validation rules' own (ValidationOptions::alpha_m), which Error Descent receives.
const double kAlpha = ValidationOptions{}.alpha_m;

using testing::RealScan;

std::string Report(const RefinementResult& r) {
  std::ostringstream os;
  os << "pose " << r.T_world_laser << " converged " << r.converged << " postures " << r.iterations
     << " EV " << r.test_before.expect_value_m << " -> " << r.test_after.expect_value_m << " MP "
     << r.test_before.match_pairs << " -> " << r.test_after.match_pairs << "/"
     << r.test_after.valid_pairs << " time " << r.time_s << " s";
  return os.str();
}

const Pose2D kTrue(3.2, 2.5, 0.3);

TEST(ErrorDescent, RecoversTruePoseWithinFiveMillimetresFromSmallOffsetsNoiseFree) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  const MapView map{&lines, nullptr};
  // Offsets off the search lattice (multiples of 0.625 mm / 0.0625 mrad), so that the true posture
  // is never among the postures examined.
  for (const Pose2D& offset : {Pose2D(0.0317, -0.0213, 0.0191), Pose2D(-0.0388, 0.0291, -0.0147),
                               Pose2D(0.0523, 0.0109, 0.0213), Pose2D(-0.0196, -0.0481, -0.0202)}) {
    const Pose2D initial(kTrue.x_m + offset.x_m, kTrue.y_m + offset.y_m,
                         kTrue.yaw_rad + offset.yaw_rad);
    const RefinementResult r = RefineErrorDescent(map, scan, initial, ScoringOptions{}, kAlpha);
    SCOPED_TRACE("offset " + ::testing::PrintToString(offset.x_m) + ", " +
                 ::testing::PrintToString(offset.y_m) + ", " +
                 ::testing::PrintToString(offset.yaw_rad) + ": " + Report(r));
    EXPECT_TRUE(r.converged);
    EXPECT_NEAR(r.T_world_laser.x_m, kTrue.x_m, 0.005);
    EXPECT_NEAR(r.T_world_laser.y_m, kTrue.y_m, 0.005);
    EXPECT_NEAR(r.T_world_laser.yaw_rad, kTrue.yaw_rad, 0.002);
    EXPECT_LE(r.test_after.expect_value_m, r.test_before.expect_value_m);
    EXPECT_EQ(r.test_after.match_pairs, r.test_after.valid_pairs);
  }
}

TEST(ErrorDescent, AxisMovesOnlyAlsoRecoverTruePose) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  ErrorDescentOptions options;
  options.diagonal_moves = false;
  const Pose2D initial(kTrue.x_m + 0.0317, kTrue.y_m - 0.0213, kTrue.yaw_rad + 0.0191);
  const RefinementResult r = RefineErrorDescent(MapView{&lines, nullptr}, scan, initial,
                                                ScoringOptions{}, kAlpha, options);
  SCOPED_TRACE(Report(r));
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.T_world_laser.x_m, kTrue.x_m, 0.005);
  EXPECT_NEAR(r.T_world_laser.y_m, kTrue.y_m, 0.005);
  EXPECT_NEAR(r.T_world_laser.yaw_rad, kTrue.yaw_rad, 0.002);
}

TEST(ErrorDescent, ExpectValueNeverIncreasesAndPoseImprovesWithRangeNoise) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, kNoiseSigmaM);
  const Pose2D initial(kTrue.x_m - 0.0388, kTrue.y_m + 0.0291, kTrue.yaw_rad - 0.0147);
  const RefinementResult r =
      RefineErrorDescent(MapView{&lines, nullptr}, scan, initial, ScoringOptions{}, kAlpha);
  SCOPED_TRACE(Report(r));
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.test_after.expect_value_m, r.test_before.expect_value_m);
  // With 2 cm noise on 720 beams the posture is still determined to about a centimetre.
  EXPECT_NEAR(r.T_world_laser.x_m, kTrue.x_m, 0.01);
  EXPECT_NEAR(r.T_world_laser.y_m, kTrue.y_m, 0.01);
  EXPECT_NEAR(r.T_world_laser.yaw_rad, kTrue.yaw_rad, 0.005);
}

TEST(ErrorDescent, RecoversTruePoseOnPointMapSampledFromLines) {
  const LineMap lines = testing::SmallRoomWithL();
  const PointMap points = PointMapFromLines(lines);
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  const Pose2D initial(kTrue.x_m + 0.0317, kTrue.y_m + 0.0213, kTrue.yaw_rad - 0.0147);
  const RefinementResult r =
      RefineErrorDescent(MapView{nullptr, &points}, scan, initial, ScoringOptions{}, kAlpha);
  SCOPED_TRACE(Report(r));
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.test_after.expect_value_m, r.test_before.expect_value_m);
  EXPECT_NEAR(r.T_world_laser.x_m, kTrue.x_m, 0.005);
  EXPECT_NEAR(r.T_world_laser.y_m, kTrue.y_m, 0.005);
  EXPECT_NEAR(r.T_world_laser.yaw_rad, kTrue.yaw_rad, 0.002);
}

TEST(ErrorDescent, ScoresEveryStencilOncePerLevelWhenStartingAtTheOptimum) {
  // Noise-free at the true posture every pair is in slot 0: no neighbour can improve, so each
  // level scores its stencil once and stays put: 1 + 26·7 postures (1 + 6·7 with axis moves).
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  const MapView map{&lines, nullptr};
  const RefinementResult diagonal = RefineErrorDescent(map, scan, kTrue, ScoringOptions{}, kAlpha);
  EXPECT_EQ(diagonal.iterations, 1 + 26 * 7);
  EXPECT_TRUE(diagonal.converged);
  EXPECT_DOUBLE_EQ(diagonal.T_world_laser.x_m, kTrue.x_m);
  EXPECT_DOUBLE_EQ(diagonal.T_world_laser.yaw_rad, kTrue.yaw_rad);
  ErrorDescentOptions axes;
  axes.diagonal_moves = false;
  EXPECT_EQ(RefineErrorDescent(map, scan, kTrue, ScoringOptions{}, kAlpha, axes).iterations,
            1 + 6 * 7);
}

TEST(ErrorDescent, MoveBudgetExhaustedIsReportedAsNotConverged) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  ErrorDescentOptions options;
  options.max_moves_per_level = 1;
  options.step_levels = 1;
  // 0.2 m away with 0.04 m steps needs several moves.
  const Pose2D initial(kTrue.x_m + 0.2, kTrue.y_m, kTrue.yaw_rad);
  const RefinementResult r = RefineErrorDescent(MapView{&lines, nullptr}, scan, initial,
                                                ScoringOptions{}, kAlpha, options);
  EXPECT_FALSE(r.converged);
  EXPECT_NEAR(r.T_world_laser.x_m, initial.x_m - 0.04, 1e-12);
}

TEST(ErrorDescent, EmptyMapOrAllInvalidScanGivesInitialPoseNotConverged) {
  const LineMap lines = testing::SmallRoomWithL();
  const LineMap empty;
  LaserScan scan = RealScan(lines, kTrue, 0.0);
  const Pose2D initial(kTrue.x_m + 0.03, kTrue.y_m, kTrue.yaw_rad);

  const RefinementResult no_map =
      RefineErrorDescent(MapView{&empty, nullptr}, scan, initial, ScoringOptions{}, kAlpha);
  EXPECT_FALSE(no_map.converged);
  EXPECT_EQ(no_map.test_after.valid_pairs, 0);
  EXPECT_DOUBLE_EQ(no_map.T_world_laser.x_m, initial.x_m);

  for (double& range : scan.ranges_m) range = -1.0;
  const RefinementResult no_data =
      RefineErrorDescent(MapView{&lines, nullptr}, scan, initial, ScoringOptions{}, kAlpha);
  EXPECT_FALSE(no_data.converged);
  EXPECT_DOUBLE_EQ(no_data.T_world_laser.x_m, initial.x_m);
}

TEST(ErrorDescent, InvalidOptionsThrowWithMessage) {
  const LineMap lines = testing::SmallRoomWithL();
  const LaserScan scan = RealScan(lines, kTrue, 0.0);
  const MapView map{&lines, nullptr};
  auto expect_throw = [&](ErrorDescentOptions options, const std::string& field) {
    try {
      RefineErrorDescent(map, scan, kTrue, ScoringOptions{}, kAlpha, options);
      ADD_FAILURE() << "no exception for " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  ErrorDescentOptions o;
  o.initial_step_m = 0.0;
  expect_throw(o, "initial_step_m");
  o = {};
  o.initial_step_rad = -1.0;
  expect_throw(o, "initial_step_rad");
  o = {};
  o.step_levels = 0;
  expect_throw(o, "step_levels");
  o = {};
  o.step_levels = 31;
  expect_throw(o, "step_levels");
  o = {};
  o.max_moves_per_level = 0;
  expect_throw(o, "max_moves_per_level");
  EXPECT_THROW(RefineErrorDescent(map, scan, kTrue, ScoringOptions{}, std::nan("")),
               std::invalid_argument);
  EXPECT_THROW(RefineErrorDescent(map, scan, kTrue, ScoringOptions{}, -0.1), std::invalid_argument);
  EXPECT_THROW(RefineErrorDescent(map, scan, Pose2D(std::nan(""), 0, 0), ScoringOptions{}, kAlpha),
               std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
