// The report's side of loop closure: a record's accepted closure is read back (the old scan it
// closed with) and drawn on the trajectory figure; a closure that was not accepted is not.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/io/run_folder.hpp"
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

}  // namespace
}  // namespace scanloc
