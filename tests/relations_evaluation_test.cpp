#include "scanloc/evaluation/relations_evaluation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/trajectory.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

constexpr double kTolerance = 1e-9;
// 0.2 rad and 0.1 rad in degrees.
constexpr double kPointTwoRadDeg = 11.459155902616464;
constexpr double kPointOneRadDeg = 5.729577951308232;

using testing::WriteText;

// Robot poses at t = 1, 2, 3: it moves 1 m along its heading (+y), then turns by 0.2 rad.
std::vector<StampedPose> HandTrajectory() {
  return {{2.0, Pose2D(1.0, 3.0, M_PI / 2)},  // out of time order on purpose
          {1.0, Pose2D(1.0, 2.0, M_PI / 2)},
          {3.0, Pose2D(1.0, 3.0, M_PI / 2 + 0.2)}};
}

// Relations that differ from the trajectory's relative motions by known errors e = δ ⊖ δ*:
//   1→2: δ = (1, 0, 0),   δ* = (0.7, 0.4, 0)  → e = (0.3, −0.4, 0): 0.5 m, 0°
//   2→3: δ = (0, 0, 0.2), δ* = (0, 0, 0)      → e = (0, 0, 0.2):   0 m, 11.459°
//   1→3: δ = (1, 0, 0.2), δ* = (1, 0, 0.3)    → e = (0, 0, −0.1):  0 m, 5.730°
std::vector<Relation> HandRelations() {
  return {{1.0, 2.0, Pose2D(0.7, 0.4, 0.0)},
          {2.0, 3.0, Pose2D(0.0, 0.0, 0.0)},
          {1.0, 3.0, Pose2D(1.0, 0.0, 0.3)}};
}

TEST(RelationsEvaluation, ErrorsAreTheKnownOffsetsBetweenEstimateAndRelations) {
  const RelationsEvaluation evaluation = EvaluateRelations(HandTrajectory(), HandRelations());
  EXPECT_EQ(evaluation.matched, 3u);
  EXPECT_EQ(evaluation.unmatched, 0u);
  ASSERT_EQ(evaluation.errors.size(), 3u);
  EXPECT_NEAR(evaluation.errors[0].x_m, 0.3, kTolerance);
  EXPECT_NEAR(evaluation.errors[0].y_m, -0.4, kTolerance);
  EXPECT_NEAR(evaluation.errors[0].yaw_rad, 0.0, kTolerance);
  EXPECT_NEAR(evaluation.errors[1].yaw_rad, 0.2, kTolerance);
  EXPECT_NEAR(evaluation.errors[2].x_m, 0.0, kTolerance);
  EXPECT_NEAR(evaluation.errors[2].y_m, 0.0, kTolerance);
  EXPECT_NEAR(evaluation.errors[2].yaw_rad, -0.1, kTolerance);
}

// A robot passes a place going east, then comes back going west, its laser 0.04 m ahead of its
// base. The scans' relation of the two passes is what the scans saw: the laser poses are
// (0.04, 0, 0) and (-0.04, 0, π), 0.08 m apart. The robot's poses are both at the origin, so
// scoring them on that relation is wrong by the 0.08 m; their laser poses score zero.
TEST(RelationsEvaluation, RelationsOfScansScoreTheLaserPosesOfARobotTrajectory) {
  const LaserMounting mounting{Pose2D(0.04, 0.0, 0.0)};
  const std::vector<StampedPose> robot = {{1.0, Pose2D(0.0, 0.0, 0.0)},
                                          {2.0, Pose2D(0.0, 0.0, M_PI)}};
  const std::vector<Relation> scans = {
      {1.0, 2.0, Between(mounting.LaserPose(robot[0].pose), mounting.LaserPose(robot[1].pose))}};
  EXPECT_NEAR(scans[0].T_1_2.x_m, -0.08, kTolerance);
  EXPECT_NEAR(EvaluateRelations(robot, scans).translation_m.mean, 0.08, kTolerance);
  const std::vector<StampedPose> laser = LaserPoses(robot, mounting);
  ASSERT_EQ(laser.size(), 2u);
  EXPECT_DOUBLE_EQ(laser[1].timestamp_s, 2.0);
  EXPECT_NEAR(laser[1].pose.x_m, -0.04, kTolerance);
  EXPECT_NEAR(EvaluateRelations(laser, scans).translation_m.mean, 0.0, kTolerance);
  EXPECT_NEAR(EvaluateRelations(laser, scans).rotation_deg.mean, 0.0, kTolerance);
}

TEST(RelationsEvaluation, StatisticsAreHandComputedPopulationMeanStdAndMax) {
  const RelationsEvaluation evaluation = EvaluateRelations(HandTrajectory(), HandRelations());
  // Translations {0.5, 0, 0} m.
  EXPECT_NEAR(evaluation.translation_m.mean, 0.5 / 3, kTolerance);
  EXPECT_NEAR(evaluation.translation_m.std, std::sqrt(2.0) / 6, kTolerance);
  EXPECT_NEAR(evaluation.translation_m.max, 0.5, kTolerance);
  // Squares {0.25, 0, 0} m².
  EXPECT_NEAR(evaluation.translation_squared_m2.mean, 0.25 / 3, kTolerance);
  EXPECT_NEAR(evaluation.translation_squared_m2.std, std::sqrt(2.0) / 12, kTolerance);
  EXPECT_NEAR(evaluation.translation_squared_m2.max, 0.25, kTolerance);
  // Rotations {0, 2a, a} deg with a = 0.1 rad: mean a, std a·√(2/3).
  const double a = kPointOneRadDeg;
  EXPECT_NEAR(evaluation.rotation_deg.mean, a, kTolerance);
  EXPECT_NEAR(evaluation.rotation_deg.std, a * std::sqrt(2.0 / 3.0), kTolerance);
  EXPECT_NEAR(evaluation.rotation_deg.max, kPointTwoRadDeg, kTolerance);
  // Squares {0, 4a², a²}: mean 5a²/3, std a²·√26/3.
  EXPECT_NEAR(evaluation.rotation_squared_deg2.mean, 5 * a * a / 3, 1e-7);
  EXPECT_NEAR(evaluation.rotation_squared_deg2.std, a * a * std::sqrt(26.0) / 3, 1e-7);
  EXPECT_NEAR(evaluation.rotation_squared_deg2.max, 4 * a * a, 1e-7);
}

TEST(RelationsEvaluation, ExactRelationsScoreZero) {
  std::vector<Relation> relations = HandRelations();
  relations[0].T_1_2 = Pose2D(1.0, 0.0, 0.0);
  relations[1].T_1_2 = Pose2D(0.0, 0.0, 0.2);
  relations[2].T_1_2 = Pose2D(1.0, 0.0, 0.2);
  const RelationsEvaluation evaluation = EvaluateRelations(HandTrajectory(), relations);
  EXPECT_EQ(evaluation.matched, 3u);
  EXPECT_NEAR(evaluation.translation_m.max, 0.0, kTolerance);
  EXPECT_NEAR(evaluation.rotation_deg.max, 0.0, kTolerance);
}

TEST(RelationsEvaluation, MatchesTheNearestTimestampWithinTheTolerance) {
  // Two poses either side of t = 2: the nearer one (2.0004) is used.
  const std::vector<StampedPose> trajectory = {
      {1.0, Pose2D(0, 0, 0)}, {1.9995, Pose2D(5.0, 0, 0)}, {2.0004, Pose2D(1.0, 0, 0)}};
  const RelationsEvaluation evaluation =
      EvaluateRelations(trajectory, {{1.0, 2.0, Pose2D(1.0, 0, 0)}});
  EXPECT_EQ(evaluation.matched, 1u);
  EXPECT_NEAR(evaluation.translation_m.mean, 0.0, kTolerance);

  RelationsEvaluationOptions strict;
  strict.timestamp_tolerance_s = 1e-4;
  EXPECT_EQ(EvaluateRelations(trajectory, {{1.0, 2.0, Pose2D(1.0, 0, 0)}}, strict).matched, 0u);
}

TEST(RelationsEvaluation, RelationsOutsideTheTrajectoryAreCountedAndReported) {
  std::vector<Relation> relations = HandRelations();
  relations.push_back({3.0, 4.0, Pose2D()});   // t2 absent
  relations.push_back({0.99, 2.0, Pose2D()});  // t1 10 ms off, beyond the 1 ms tolerance
  const RelationsEvaluation evaluation = EvaluateRelations(HandTrajectory(), relations);
  EXPECT_EQ(evaluation.matched, 3u);
  EXPECT_EQ(evaluation.unmatched, 2u);
  ASSERT_EQ(evaluation.unmatched_relations.size(), 2u);
  EXPECT_NEAR(evaluation.unmatched_relations[0].t2_s, 4.0, kTolerance);
  EXPECT_NEAR(evaluation.unmatched_relations[1].t1_s, 0.99, kTolerance);
  // The statistics cover the matched relations only.
  EXPECT_NEAR(evaluation.translation_m.mean, 0.5 / 3, kTolerance);
}

TEST(RelationsEvaluation, NothingMatchedGivesZeroStatistics) {
  const RelationsEvaluation evaluation = EvaluateRelations({}, HandRelations());
  EXPECT_EQ(evaluation.matched, 0u);
  EXPECT_EQ(evaluation.unmatched, 3u);
  EXPECT_EQ(evaluation.translation_m.mean, 0.0);
  EXPECT_EQ(evaluation.rotation_deg.max, 0.0);
}

TEST(RelationsEvaluation, RejectsANegativeTolerance) {
  RelationsEvaluationOptions options;
  options.timestamp_tolerance_s = -1.0;
  EXPECT_THROW(EvaluateRelations(HandTrajectory(), HandRelations(), options),
               std::invalid_argument);
}

TEST(RelationsEvaluation, ReadsRelationsFile) {
  const std::string path =
      WriteText(testing::TemporaryDir() + "/x.relations",
                "976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 0.000000 "
                "0.000000 -1.682210\n\n"
                "1.5 2.5 0.4 -0.01 0 0 0 3.5\n");
  const std::vector<Relation> relations = ReadRelations(path);
  ASSERT_EQ(relations.size(), 2u);
  EXPECT_NEAR(relations[0].t1_s, 976052905.167303, 1e-6);
  EXPECT_NEAR(relations[0].t2_s, 976052911.885496, 1e-6);
  EXPECT_NEAR(relations[0].T_1_2.x_m, -0.05699, kTolerance);
  EXPECT_NEAR(relations[0].T_1_2.y_m, -0.12843, kTolerance);
  EXPECT_NEAR(relations[0].T_1_2.yaw_rad, -1.68221, kTolerance);
  EXPECT_NEAR(relations[1].T_1_2.yaw_rad, 3.5 - 2 * M_PI, kTolerance);  // normalised
}

TEST(RelationsEvaluation, MalformedRelationsNameFileLineAndExpectation) {
  const std::string dir = testing::TemporaryDir();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"1 2 0.1 0.2 0 0 0", "8 fields"},
      {"1 2 0.1 y 0 0 0 0.1", "'y'"},
      {"1 2 0.1 0.2 0.5 0 0 0.1", "planar"},
      {"1 2 0.1 0.2 0 0.1 0 0.1", "planar"},
  };
  for (const auto& [line, expected] : cases) {
    const std::string path = WriteText(dir + "/bad.relations", "1 2 0 0 0 0 0 0\n" + line + "\n");
    std::string message;
    try {
      ReadRelations(path);
    } catch (const ParseError& error) {
      message = error.what();
    }
    EXPECT_NE(message.find("bad.relations:2:"), std::string::npos) << line << " -> " << message;
    EXPECT_NE(message.find(expected), std::string::npos) << line << " -> " << message;
  }
  EXPECT_THROW(ReadRelations(dir + "/absent.relations"), std::runtime_error);
}

// Scores a dataset's corrected poses against its relations and prints the figures.
RelationsEvaluation ScoreCorrectedPoses(const std::string& dir, const std::string& name) {
  const RelationsEvaluation evaluation =
      EvaluateRelations(ReadCorrectedPoses(dir + "/" + name + ".corrected-poses.txt"),
                        ReadRelations(dir + "/" + name + ".relations"));
  std::printf(
      "%s corrected poses: %zu matched, %zu unmatched relations; translation %.4f ± %.4f m "
      "(max %.4f, squared %.5f ± %.5f m²); rotation %.3f ± %.3f deg (max %.3f, squared %.3f ± "
      "%.3f deg²)\n",
      name.c_str(), evaluation.matched, evaluation.unmatched, evaluation.translation_m.mean,
      evaluation.translation_m.std, evaluation.translation_m.max,
      evaluation.translation_squared_m2.mean, evaluation.translation_squared_m2.std,
      evaluation.rotation_deg.mean, evaluation.rotation_deg.std, evaluation.rotation_deg.max,
      evaluation.rotation_squared_deg2.mean, evaluation.rotation_squared_deg2.std);
  return evaluation;
}

TEST(RelationsEvaluationDatasets, IntelCorrectedPosesScoreAboutThreeAndAHalfCentimetres) {
  SCANLOC_REQUIRE_DATASETS(dir);
  const RelationsEvaluation evaluation = ScoreCorrectedPoses(dir, "intel");
  // The corrected poses cover a subset of the scans, so most relations stay unmatched.
  EXPECT_GT(evaluation.matched, 0u);
  EXPECT_EQ(evaluation.matched + evaluation.unmatched, 2984u);
  EXPECT_GE(evaluation.translation_m.mean, 0.02);
  EXPECT_LE(evaluation.translation_m.mean, 0.05);
}

TEST(RelationsEvaluationDatasets, Fr079CorrectedPosesScoreAboutSixCentimetres) {
  SCANLOC_REQUIRE_DATASETS(dir);
  const RelationsEvaluation evaluation = ScoreCorrectedPoses(dir, "fr079");
  EXPECT_EQ(evaluation.matched + evaluation.unmatched, 1685u);
  EXPECT_GE(evaluation.translation_m.mean, 0.04);
  EXPECT_LE(evaluation.translation_m.mean, 0.08);
}

TEST(RelationsEvaluationDatasets, AcesCorrectedPosesAreScoredOnTheFewMatchedRelations) {
  SCANLOC_REQUIRE_DATASETS(dir);
  const RelationsEvaluation evaluation = ScoreCorrectedPoses(dir, "aces");
  EXPECT_EQ(evaluation.matched + evaluation.unmatched, 1279u);
}

}  // namespace
}  // namespace scanloc
