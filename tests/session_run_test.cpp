// RunSession: counts, the stop flag, and an error mid-run that ends the loop but keeps what was
// done; ChooseMounting: which mounting wins.

#include "scanloc/io/session_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "scanloc/common/parse_error.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

// Scans of a rectangular room from a robot that moves 0.2 m per scan along x; throws a ParseError
// at scan `fail_at` (never when negative), as a reader does on a malformed line.
class WalkSource : public IterationSource {
 public:
  WalkSource(int scans, int fail_at) : scans_(scans), fail_at_(fail_at) {}
  bool Next(Iteration& iteration) override {
    if (next_ == fail_at_) throw ParseError("walk.log", next_ + 1, "a scan line");
    if (next_ >= scans_) return false;
    const Pose2D pose{2.0 + 0.2 * next_, 3.0, 0.0};
    iteration = {};
    iteration.timestamp_s = 10.0 + next_;
    iteration.scan = testing::NoisyScan(room_, pose, 360, 0.0, 1);
    iteration.odometry = pose;
    iteration.origin = "walk.log:" + std::to_string(next_ + 1);
    ++next_;
    return true;
  }
  LaserMounting mounting() const override { return {}; }
  double Progress() const override { return static_cast<double>(next_) / scans_; }

 private:
  LineMap room_ = testing::RectangleRoom(10.0, 6.0);
  int scans_, fail_at_, next_ = 0;
};

SessionFactory Factory() {
  return [](const IterationSource& source) {
    SessionConfig config;
    config.session.initial_pose = {2.0, 3.0, 0.0};
    return std::make_unique<Session>(config, source.mounting(), LineMap{}, PointMap{});
  };
}

class SessionRunTest : public testing::TemporaryDirTest {};

TEST_F(SessionRunTest, CountsEveryIterationAndTheDataSpan) {
  WalkSource source(12, -1);
  RunFolder folder(dir_ + "/run");
  const SessionRun run = RunSession(source, Factory(), folder, {0, false, nullptr, {}});
  ASSERT_NE(run.session, nullptr);
  EXPECT_EQ(run.counts.iterations, 12u);
  EXPECT_EQ(run.counts.localised + run.counts.skipped, 12u);
  EXPECT_EQ(run.counts.validated + run.counts.flagged + run.counts.skipped, 12u);
  EXPECT_GE(run.counts.validated, 11u);  // the first scan and every localised one of a clean room
  EXPECT_DOUBLE_EQ(run.counts.span_s(), 11.0);
  EXPECT_TRUE(run.counts.failure.empty());
  const nlohmann::json summary = SummaryJson(run, source);
  EXPECT_EQ(summary["iterations"], 12);
  EXPECT_FALSE(summary.contains("failed"));
}

TEST_F(SessionRunTest, AnErrorMidRunEndsTheLoopAndKeepsWhatWasDone) {
  WalkSource source(12, 5);
  RunFolder folder(dir_ + "/run");
  const SessionRun run = RunSession(source, Factory(), folder, {0, false, nullptr, {}});
  EXPECT_EQ(run.counts.iterations, 5u);
  EXPECT_NE(run.counts.failure.find("walk.log:6:"), std::string::npos) << run.counts.failure;
  const nlohmann::json summary = SummaryJson(run, source);
  EXPECT_EQ(summary["failed"], run.counts.failure);
  std::ifstream records(dir_ + "/run/iterations.jsonl");
  std::string line;
  int lines = 0;
  while (std::getline(records, line)) ++lines;
  EXPECT_EQ(lines, 5);
}

TEST_F(SessionRunTest, MaxScansAndTheStopFlagEndTheLoopEarly) {
  WalkSource source(12, -1);
  RunFolder folder(dir_ + "/run");
  EXPECT_EQ(RunSession(source, Factory(), folder, {3, false, nullptr, {}}).counts.iterations, 3u);
  const std::atomic<bool> stop{true};
  WalkSource again(12, -1);
  RunFolder other(dir_ + "/other");
  const SessionRun stopped = RunSession(again, Factory(), other, {0, false, &stop, {}});
  EXPECT_EQ(stopped.counts.iterations, 0u);
  EXPECT_TRUE(stopped.counts.interrupted);
  EXPECT_EQ(stopped.session, nullptr);
  EXPECT_EQ(SummaryJson(stopped, again)["problem"], "the sequence has no scan");
}

TEST_F(SessionRunTest, ValidatedScansAreCastIntoTheOccupancyGridAtTheKeptPostures) {
  WalkSource source(12, -1);
  RunFolder folder(dir_ + "/run");
  SessionRunOptions options;
  options.progress = false;
  options.occupancy_grid = OccupancyGridOptions{};
  const SessionRun run = RunSession(source, Factory(), folder, options);
  ASSERT_TRUE(run.grid.has_value());
  EXPECT_EQ(run.grid->scans(), run.counts.validated);  // the walk's first scan is validated too
  EXPECT_GE(run.grid->scans(), 11u);
  const OccupancyGrid grid = run.grid->Build();
  EXPECT_DOUBLE_EQ(grid.resolution_m, 0.05);
  std::size_t x = 0, y = 0;
  // The south wall (y = 0) below the walk is occupied, the walk's corridor (crossed by the beams
  // of every scan) free.
  ASSERT_TRUE(grid.CellOf({3.01, 0.01}, x, y));
  EXPECT_EQ(grid.State(x, y), CellState::kOccupied);
  ASSERT_TRUE(grid.CellOf({3.01, 3.01}, x, y));
  EXPECT_EQ(grid.State(x, y), CellState::kFree);
  // Without the option, no grid is kept.
  WalkSource again(3, -1);
  RunFolder other(dir_ + "/other");
  EXPECT_FALSE(RunSession(again, Factory(), other, {0, false, nullptr, {}}).grid.has_value());
}

TEST_F(SessionRunTest, ANonEmptyRunFolderIsRefusedUnlessOverwriteIsAsked) {
  Write("kept.txt", "earlier results");
  EXPECT_THROW(RunFolder folder(dir_), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/iterations.jsonl"));  // nothing touched
  RunFolder folder(dir_, /*overwrite=*/true);
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/iterations.jsonl"));
}

TEST(ChooseMounting, TheConfiguredMountingWinsUnlessTheCommandLineOverridesTheSource) {
  const LaserMounting from_log{{0.1, 0.0, 0.0}}, configured{{0.3, 0.05, 0.01}}, none{};
  EXPECT_DOUBLE_EQ(ChooseMounting(from_log, configured, false).T_robot_laser.x_m, 0.3);
  EXPECT_DOUBLE_EQ(ChooseMounting(from_log, configured, true).T_robot_laser.x_m, 0.1);
  EXPECT_DOUBLE_EQ(ChooseMounting(from_log, none, false).T_robot_laser.x_m, 0.1);
}

}  // namespace
}  // namespace scanloc
