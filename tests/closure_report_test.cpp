// The report's side of loop closure: a record's accepted closure is read back (the old scan it
// closed with) and drawn on the trajectory figure; a closure that was not accepted is not.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/io/run_folder.hpp"
#include "scanloc/report/closure_figure.hpp"
#include "scanloc/report/figure_style.hpp"
#include "scanloc/report/run_records.hpp"
#include "scanloc/report/trajectory_figure.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

IterationRecord Walked(std::size_t index) {
  IterationRecord record;
  record.index = index;
  record.timestamp_s = static_cast<double>(index);
  record.T_world_robot = Pose2D(0.5 * static_cast<double>(index), 0.0, 0.0);
  record.prediction = record.T_world_robot;
  record.validated = true;
  return record;
}

ClosureAttempt Closure(std::size_t old_iteration, bool accepted) {
  ClosureAttempt closure;
  closure.old_iteration = old_iteration;
  closure.accepted = accepted;
  closure.reason = accepted ? "accepted" : "pending: 1 of 3 agreeing scans";
  return closure;
}

TEST(ClosureReport, AnAcceptedClosureIsReadBackWithTheOldScanAndOthersAreNot) {
  IterationRecord accepted = Walked(12), pending = Walked(13);
  accepted.closure = Closure(2, true);
  pending.closure = Closure(3, false);
  const IterationRow row = IterationRowFromJson(ToJson(accepted).dump());
  ASSERT_TRUE(row.closed_with().has_value());
  EXPECT_EQ(*row.closed_with(), 2u);
  EXPECT_FALSE(IterationRowFromJson(ToJson(pending).dump()).closed_with().has_value());
  EXPECT_FALSE(IterationRowFromJson(ToJson(Walked(14)).dump()).closed_with().has_value());
}

TEST(ClosureReport, AClosuresMeasurementIsReadBackOnlyWhenAPostureWasRefined) {
  IterationRecord measured = Walked(12), unmeasured = Walked(13);
  measured.closure = Closure(2, false);
  measured.closure->node = 7;
  measured.closure->old_node = 1;
  measured.closure->T_old_robot = Pose2D(4.5, -0.25, 0.125);
  measured.closure->test = LikelihoodTestResult{};
  unmeasured.closure = Closure(3, false);
  unmeasured.closure->reason = "nothing was refined";
  const IterationRow row = IterationRowFromJson(ToJson(measured).dump());
  ASSERT_TRUE(row.closure.has_value());
  EXPECT_EQ(row.closure->node, 7u);
  EXPECT_EQ(row.closure->old_node, 1u);
  EXPECT_EQ(row.closure->old_iteration, 2u);
  EXPECT_EQ(row.closure->reason, "pending: 1 of 3 agreeing scans");
  ASSERT_TRUE(row.closure->T_old_robot.has_value());
  EXPECT_EQ(row.closure->T_old_robot->x_m, 4.5);
  EXPECT_EQ(row.closure->T_old_robot->yaw_rad, 0.125);
  const IterationRow none = IterationRowFromJson(ToJson(unmeasured).dump());
  ASSERT_TRUE(none.closure.has_value());
  EXPECT_FALSE(none.closure->T_old_robot.has_value());
}

TEST(ClosureReport, AClosureWithANegativeOldScanIsRefusedNamingTheField) {
  IterationRecord record = Walked(12);
  record.closure = Closure(2, true);
  nlohmann::json json = ToJson(record);
  json["closure"]["old_iteration"] = -2;
  try {
    IterationRowFromJson(json.dump());
    FAIL() << "a negative old scan was read";
  } catch (const std::runtime_error& error) {
    EXPECT_TRUE(testing::Contains(error.what(), "closure.old_iteration")) << error.what();
  }
}

TEST(ClosureReport, TheTrajectoryFigureDrawsAcceptedClosuresWithTheirLegend) {
  std::vector<IterationRow> rows;
  for (std::size_t i = 0; i < 20; ++i) {
    IterationRecord record = Walked(i);
    if (i == 15) record.closure = Closure(1, true);
    if (i == 17) record.closure = Closure(4, false);
    rows.push_back(IterationRowFromJson(ToJson(record).dump()));
  }
  TrajectoryFigureInput input;
  input.rows = &rows;
  const std::string svg = TrajectoryFigure(input, "closures");
  EXPECT_TRUE(testing::Contains(svg, "loop closures (accepted)"));
  // One closure line and the legend's sample: two strokes of the closure colour.
  std::size_t strokes = 0;
  for (std::size_t at = svg.find(figure_style::kClosure); at != std::string::npos;
       at = svg.find(figure_style::kClosure, at + 1))
    ++strokes;
  EXPECT_EQ(strokes, 2u);
  rows[15].closure.reset();
  EXPECT_FALSE(testing::Contains(TrajectoryFigure(input, "none"), "loop closures"));
}

// A closure matched against the old nodes at `matched` (the session had the scan at Walked's).
IterationRecord MatchedClosure(std::size_t index, const Pose2D& matched, bool accepted,
                               double largest_shift_m) {
  IterationRecord record = Walked(index);
  record.closure = Closure(1, accepted);
  record.closure->T_world_robot_matched = matched;
  record.closure->test = LikelihoodTestResult{};
  record.closure->largest_shift_m = largest_shift_m;
  return record;
}

TEST(ClosureReport, EachMatchedClosuresShiftAndTurnAreMeasuredFromTheSessionsPosture) {
  std::vector<IterationRow> rows;
  // Scan 10 is at (5, 0, 0): matched 3 cm along y and 0.02 rad turned; accepted, the solve moved a
  // node 1.5 cm. Scan 11 (5.5, 0, 0): matched 0.4 m off, not accepted. Scan 12: nothing refined.
  rows.push_back(IterationRowFromJson(
      ToJson(MatchedClosure(10, Pose2D(5.0, 0.03, 0.02), true, 0.015)).dump()));
  rows.push_back(IterationRowFromJson(
      ToJson(MatchedClosure(11, Pose2D(5.5, 0.4, -0.1), false, 0.0)).dump()));
  IterationRecord unmatched = Walked(12);
  unmatched.closure = Closure(2, false);
  rows.push_back(IterationRowFromJson(ToJson(unmatched).dump()));
  const std::vector<ClosureSample> samples = ClosureSamples(rows);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].index, 10u);
  EXPECT_EQ(samples[0].old_iteration, 1u);
  EXPECT_TRUE(samples[0].accepted);
  EXPECT_NEAR(samples[0].shift_m, 0.03, 1e-12);
  EXPECT_NEAR(samples[0].heading_rad, 0.02, 1e-12);
  ASSERT_TRUE(samples[0].applied_m.has_value());
  EXPECT_NEAR(*samples[0].applied_m, 0.015, 1e-12);
  EXPECT_FALSE(samples[1].accepted);
  EXPECT_NEAR(samples[1].shift_m, 0.4, 1e-12);
  EXPECT_NEAR(samples[1].heading_rad, -0.1, 1e-12);
  EXPECT_FALSE(samples[1].applied_m.has_value());  // only an accepted closure moves the graph
}

TEST(ClosureReport, TheCorrectionFigureDrawsEveryMatchedClosureOrSaysThereIsNone) {
  std::vector<IterationRow> rows;
  for (std::size_t i = 0; i < 20; ++i) {
    IterationRecord record = Walked(i);
    if (i == 15) record = MatchedClosure(15, Pose2D(7.5, 0.05, 0.01), true, 0.04);
    if (i == 17) record = MatchedClosure(17, Pose2D(8.5, 0.9, 0.3), false, 0.0);
    rows.push_back(IterationRowFromJson(ToJson(record).dump()));
  }
  const std::string svg = ClosureCorrectionFigure(rows, "closures");
  // Each closure has a tooltip naming its scans; the accepted one its node shift.
  EXPECT_TRUE(testing::Contains(svg, "scan 15 with scan 1, accepted: 5.0 cm, 0.57°; the graph "
                                     "moved a node 4.0 cm"));
  EXPECT_TRUE(testing::Contains(svg, "scan 17 with scan 1, not accepted: 90.0 cm, 17.19°"));
  EXPECT_FALSE(testing::Contains(svg, "no loop closure was matched"));
  for (IterationRow& row : rows) row.closure.reset();
  EXPECT_TRUE(testing::Contains(ClosureCorrectionFigure(rows, "none"),
                                "no loop closure was matched: no correction to draw"));
}

}  // namespace
}  // namespace scanloc
