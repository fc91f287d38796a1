// Closure precision: how many of a session's loop closures were right against reference poses,
// in the library (EvaluateClosures) and through `scanloc evaluate --closures RUN --reference P`
// on a run folder written by hand: records with closures right, wrong, unmeasured and set aside.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "scanloc/evaluation/closure_precision.hpp"
#include "scanloc/graph/pose_graph.hpp"
#include "scanloc/io/g2o_file.hpp"
#include "scanloc/io/run_folder.hpp"
#include "scanloc/io/trajectory.hpp"
#include "scanloc/session/scan_processor.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

constexpr double kTolerance = 1e-9;
constexpr std::size_t kScans = 16;

// The reference: at t = i s the robot stands at (0.5 i, 0.1 i) heading 0.05 i rad.
Pose2D Truth(std::size_t i) {
  const double k = static_cast<double>(i);
  return Pose2D(0.5 * k, 0.1 * k, 0.05 * k);
}

std::vector<StampedPose> Reference(double time_shift_s = 0.0) {
  std::vector<StampedPose> poses;
  for (std::size_t i = 0; i < kScans; ++i)
    poses.push_back({static_cast<double>(i) + time_shift_s, Truth(i)});
  return poses;
}

// Scan `now` seen from scan `old`, `off_m` metres wrong along x.
ClosureMeasurement Measured(std::size_t old, std::size_t now, double off_m, bool accepted,
                            bool in_graph) {
  Pose2D T_old_robot = Between(Truth(old), Truth(now));
  T_old_robot.x_m += off_m;
  return {static_cast<double>(old), static_cast<double>(now), T_old_robot, accepted, in_graph};
}

TEST(ClosurePrecision, RightAndWrongClosuresAreCountedPerGroup) {
  std::vector<ClosureMeasurement> closures = {
      Measured(2, 10, 0.0, true, true),    // right, accepted, kept
      Measured(3, 11, 0.3, false, true),   // 0.3 m wrong, kept
      Measured(4, 12, 0.05, true, false),  // right (within 0.1 m), accepted, set aside
      Measured(5, 13, 0.0, false, false),  // no reference pose for the old scan (below)
  };
  closures[3].t_old_s = 100.0;
  const ClosurePrecision p = EvaluateClosures(closures, Reference());
  EXPECT_EQ(p.measured.closures, 4u);
  EXPECT_EQ(p.measured.evaluation.matched, 3u);
  EXPECT_EQ(p.measured.right, 2u);
  EXPECT_EQ(p.accepted.closures, 2u);
  EXPECT_EQ(p.accepted.right, 2u);
  EXPECT_NEAR(p.accepted.evaluation.translation_m.max, 0.05, kTolerance);
  EXPECT_EQ(p.in_graph.closures, 2u);
  EXPECT_EQ(p.in_graph.right, 1u);
  ASSERT_EQ(p.errors.size(), 4u);
  ASSERT_TRUE(p.errors[1].has_value());
  EXPECT_NEAR(p.errors[1]->Translation().norm(), 0.3, kTolerance);
  EXPECT_FALSE(p.errors[3].has_value());
  EXPECT_EQ(p.right, (std::vector<bool>{true, false, true, false}));
}

TEST(ClosurePrecision, ARotationBeyondTheBoundIsWrongAndBoundsMustBePositive) {
  ClosureMeasurement turned = Measured(2, 10, 0.0, true, true);
  turned.T_old_robot.yaw_rad += 2.0 * M_PI / 180.0;  // 2°
  EXPECT_EQ(EvaluateClosures({turned}, Reference()).right, std::vector<bool>{false});
  ClosurePrecisionOptions loose;
  loose.max_rotation_error_deg = 3.0;
  EXPECT_EQ(EvaluateClosures({turned}, Reference(), loose).right, std::vector<bool>{true});
  for (const double bad : {0.0, -1.0, std::nan("")}) {
    ClosurePrecisionOptions options;
    options.max_translation_error_m = bad;
    EXPECT_THROW(EvaluateClosures({turned}, Reference(), options), std::invalid_argument);
  }
}

// Scan `now` placed `off_m` metres wrong along the x axis of scan `old`.
Pose2D PlacedOff(std::size_t old, std::size_t now, double off_m) {
  Pose2D T_old_robot = Between(Truth(old), Truth(now));
  T_old_robot.x_m += off_m;
  return Truth(old) * T_old_robot;
}

// The session's own trajectory: scans 10 and 13 placed 0.2 m off as seen from scans 2 and 5, the
// rest right, and scan 12 absent.
std::vector<StampedPose> SessionTrajectory() {
  std::vector<StampedPose> poses;
  for (std::size_t i = 0; i < kScans; ++i) {
    if (i == 12) continue;
    Pose2D pose = Truth(i);
    if (i == 10) pose = PlacedOff(2, 10, 0.2);
    if (i == 13) pose = PlacedOff(5, 13, 0.2);
    poses.push_back({static_cast<double>(i), pose});
  }
  return poses;
}

TEST(ClosuresBesideTrajectory, EachClosureIsScoredBesideTheTrajectorysPostureOfItsTwoScans) {
  const std::vector<ClosureMeasurement> closures = {
      Measured(2, 10, 0.0, true, true),     // right, where the session is 0.2 m off
      Measured(3, 11, 0.3, false, true),    // 0.3 m wrong, where the session is right
      Measured(4, 12, 0.0, true, false),    // the session has no scan 12
      Measured(5, 13, 0.15, true, false),   // 0.15 m wrong, the session 0.2 m
      Measured(6, 14, 0.01, false, false),  // both right, 1 cm apart
  };
  const ClosuresBesideTrajectory beside =
      CompareWithTrajectory(closures, Reference(), SessionTrajectory());
  EXPECT_EQ(beside.compared, (std::vector<std::size_t>{0, 1, 3, 4}));
  EXPECT_EQ(beside.not_in_trajectory, 1u);
  EXPECT_EQ(beside.closures.right, (std::vector<bool>{true, false, false, true}));
  EXPECT_EQ(beside.trajectory.right, (std::vector<bool>{false, true, false, true}));
  EXPECT_EQ(beside.trajectory.accepted.closures, 2u);
  EXPECT_EQ(beside.trajectory.accepted.right, 0u);
  ASSERT_EQ(beside.disagreement_m.size(), 4u);
  EXPECT_NEAR(beside.disagreement_m[0], 0.2, kTolerance);
  EXPECT_NEAR(beside.disagreement_m[1], 0.3, kTolerance);
  EXPECT_NEAR(beside.disagreement_m[2], 0.05, kTolerance);
  EXPECT_NEAR(beside.disagreement_m[3], 0.01, kTolerance);

  const std::vector<DisagreementBin> bins = RightByDisagreement(beside, {0.02, 0.1});
  ASSERT_EQ(bins.size(), 3u);
  EXPECT_EQ(bins[0].closures, 1u);  // 1 cm
  EXPECT_EQ(bins[0].closure_right, 1u);
  EXPECT_EQ(bins[0].trajectory_right, 1u);
  EXPECT_EQ(bins[1].closures, 1u);  // 5 cm: both wrong
  EXPECT_EQ(bins[1].closure_right + bins[1].trajectory_right, 0u);
  EXPECT_EQ(bins[2].closures, 2u);  // 0.2 and 0.3 m: one right each
  EXPECT_EQ(bins[2].closure_right, 1u);
  EXPECT_EQ(bins[2].trajectory_right, 1u);
  EXPECT_TRUE(std::isinf(bins[2].to_m));
  EXPECT_THROW(RightByDisagreement(beside, {0.1, 0.02}), std::invalid_argument);
  EXPECT_THROW(RightByDisagreement(beside, {0.0}), std::invalid_argument);
}

// A run folder of kScans records along the reference, with closures written as a session does.
class EvaluateClosuresCliTest : public testing::TemporaryDirTest {
 protected:
  static IterationRecord Record(std::size_t i) {
    IterationRecord record;
    record.index = i;
    record.timestamp_s = static_cast<double>(i);
    record.T_world_robot = Truth(i);
    record.prediction = record.T_world_robot;
    record.validated = true;
    return record;
  }
  // A closure of scan `now` with scan `old`, measured `off_m` wrong (or nothing refined).
  static ClosureAttempt Closure(std::size_t old, std::size_t now, std::optional<double> off_m,
                                bool accepted) {
    ClosureAttempt closure;
    closure.iteration = closure.node = now;
    closure.old_iteration = closure.old_node = old;
    closure.accepted = accepted;
    closure.reason = accepted ? "accepted"
                     : off_m  ? "pending: 1 of 3 agreeing scans"
                              : "nothing was refined";
    if (off_m) {
      closure.T_old_robot = Between(Truth(old), Truth(now));
      closure.T_old_robot.x_m += *off_m;
      closure.test = LikelihoodTestResult{};
    }
    return closure;
  }
  // Records 10 (right, accepted, kept), 11 (0.3 m wrong, kept), 12 (nothing refined) and 13
  // (0.3 m wrong, accepted, set aside), and the graph holding closures 2→10 and 3→11.
  void WriteRun(bool with_closures = true) {
    std::filesystem::create_directories(dir_ + "/run");
    std::string records;
    PoseGraph graph;
    for (std::size_t i = 0; i < kScans; ++i) {
      IterationRecord record = Record(i);
      if (with_closures && i == 10) record.closure = Closure(2, 10, 0.0, true);
      if (with_closures && i == 11) record.closure = Closure(3, 11, 0.3, false);
      if (with_closures && i == 12) record.closure = Closure(4, 12, std::nullopt, false);
      if (with_closures && i == 13) record.closure = Closure(5, 13, 0.3, true);
      records += ToJson(record).dump() + "\n";
      graph.AddNode(Truth(i));
      if (i > 0) graph.AddEdge({i - 1, i, Between(Truth(i - 1), Truth(i))});
    }
    graph.AddEdge(
        {2, 10, Between(Truth(2), Truth(10)), Eigen::Matrix3d::Identity(), EdgeKind::kClosure});
    graph.AddEdge(
        {3, 11, Between(Truth(3), Truth(11)), Eigen::Matrix3d::Identity(), EdgeKind::kClosure});
    Write("run/iterations.jsonl", records);
    WriteTumTrajectory(dir_ + "/run/trajectory-online.tum", SessionTrajectory());
    WriteG2o(graph, dir_ + "/run/graph.g2o");
    WriteTumTrajectory(dir_ + "/reference.tum", Reference());
  }
  testing::ScanlocRun Evaluate(const std::string& reference, bool json = false) {
    std::vector<std::string> arguments = {"evaluate", "--closures", dir_ + "/run", "--reference",
                                          reference};
    if (json) arguments.push_back("--json");
    return testing::RunScanloc(arguments, dir_);
  }
};

using testing::Contains;

TEST_F(EvaluateClosuresCliTest, CountsTheRightClosuresAmongTheAcceptedAndThoseInTheGraph) {
  WriteRun();
  const auto run = Evaluate(dir_ + "/reference.tum", true);
  ASSERT_TRUE(run.exited && run.exit_code == 0) << run;
  const auto out = nlohmann::json::parse(run.out);
  EXPECT_EQ(out["tried"], 4);
  EXPECT_EQ(out["measured"]["closures"], 3);
  EXPECT_EQ(out["measured"]["right"], 1);
  EXPECT_EQ(out["accepted"]["closures"], 2);
  EXPECT_EQ(out["accepted"]["right"], 1);
  EXPECT_EQ(out["in_graph"]["closures"], 2);
  EXPECT_EQ(out["in_graph"]["right"], 1);
  ASSERT_EQ(out["closures"].size(), 3u);
  EXPECT_EQ(out["closures"][1]["iteration"], 11);
  EXPECT_NEAR(out["closures"][1]["error"]["translation_m"].get<double>(), 0.3, 1e-9);
  EXPECT_EQ(out["closures"][2]["in_graph"], false);
  const auto text = Evaluate(dir_ + "/reference.tum");
  EXPECT_TRUE(Contains(text.out, "4 tried, 3 measured, 2 accepted, 2 in the graph")) << text;
  EXPECT_TRUE(Contains(text.out, "accepted         1 of    2 ( 50 %)")) << text;
}

TEST_F(EvaluateClosuresCliTest, TheClosuresAreSetBesideTheSessionsOwnPostures) {
  WriteRun();
  const auto run = Evaluate(dir_ + "/reference.tum", true);
  ASSERT_TRUE(run.exited && run.exit_code == 0) << run;
  const auto session = nlohmann::json::parse(run.out)["session"];
  EXPECT_EQ(session["trajectory"], "trajectory-online.tum");
  EXPECT_EQ(session["compared"], 3);           // the measured closures 2→10, 3→11 and 5→13
  EXPECT_EQ(session["measured"]["right"], 1);  // 3→11: the session is right, the closure not
  EXPECT_EQ(session["accepted"]["right"], 0);  // 2→10 and 5→13: the session is 0.2 m off
  EXPECT_EQ(session["in_graph"]["right"], 1);  // 3→11
  const auto bins = session["by_disagreement"];
  ASSERT_EQ(bins.size(), 5u);
  EXPECT_EQ(bins[3]["closures"], 1);  // 5→13: 0.3 m against 0.2 m, 0.1 m apart, both wrong
  EXPECT_EQ(bins[3]["closure_right"], 0);
  EXPECT_EQ(bins[3]["session_right"], 0);
  EXPECT_EQ(bins[4]["closures"], 2);  // 0.2 and 0.3 m apart
  EXPECT_EQ(bins[4]["closure_right"], 1);
  EXPECT_EQ(bins[4]["session_right"], 1);
  EXPECT_TRUE(bins[4]["to_m"].is_null());
  const auto closures = nlohmann::json::parse(run.out)["closures"];
  ASSERT_EQ(closures.size(), 3u);
  EXPECT_NEAR(closures[0]["moved_from_session_m"].get<double>(), 0.2, 1e-5);  // 2→10
  EXPECT_EQ(closures[0]["session_right"], false);
  EXPECT_EQ(closures[1]["session_right"], true);  // 3→11
  const auto text = Evaluate(dir_ + "/reference.tum");
  EXPECT_TRUE(Contains(text.out, "the session's own postures of the same scans")) << text;
  std::filesystem::remove(dir_ + "/run/trajectory-online.tum");
  const auto without = Evaluate(dir_ + "/reference.tum", true);
  ASSERT_TRUE(without.exited && without.exit_code == 0) << without;
  EXPECT_TRUE(nlohmann::json::parse(without.out)["session"].is_null());
  EXPECT_TRUE(Contains(without.err, "no trajectory-online.tum")) << without;
}

TEST_F(EvaluateClosuresCliTest, ARunWithoutClosuresOrWithAnotherLogsReferenceFailsSayingWhy) {
  WriteRun(false);
  const auto none = Evaluate(dir_ + "/reference.tum");
  ASSERT_TRUE(none.exited) << none;
  EXPECT_NE(none.exit_code, 0) << none;
  EXPECT_TRUE(Contains(none.err, "no loop closure was tried")) << none;
  WriteRun();
  WriteTumTrajectory(dir_ + "/other.tum", Reference(1000.0));
  const auto other = Evaluate(dir_ + "/other.tum");
  EXPECT_NE(other.exit_code, 0) << other;
  EXPECT_TRUE(Contains(other.err, "no measured closure has reference poses")) << other;
  const auto both = testing::RunScanloc(
      {"evaluate", "--closures", dir_ + "/run", "--reference", dir_ + "/reference.tum",
       "--trajectory", dir_ + "/reference.tum", "--relations", Write("r.relations", "")},
      dir_);
  EXPECT_NE(both.exit_code, 0) << both;
  EXPECT_TRUE(Contains(both.err, "excludes")) << both;
}

}  // namespace
}  // namespace scanloc
