// Resuming a session (RunFolder opened with kResume, RunSession replaying its records): a run cut
// off part way and resumed ends with the files of an uninterrupted one, loop closure's graph
// included; records that disagree with the replay, a shorter log, another identity and a broken
// record are refused, and the folder is left as it was.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/run_folder.hpp"
#include "scanloc/io/session_run.hpp"
#include "scanloc/worlds/laser_simulator.hpp"
#include "scanloc/worlds/robot_path.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

// One lap and a bit of the ring building every 0.4 m with a 181-beam laser, and odometry with
// 0.5 % scale and 1.3 % heading error: the session localises every scan, extends its map, and
// comes back to where it started (a closure is due).
struct Drive {
  std::vector<LaserScan> scans;
  std::vector<Pose2D> odometry;
};

const Drive& RingDrive() {
  static const Drive drive = [] {
    RobotPathOptions path;
    path.step_m = 0.4;
    const std::vector<Pose2D> truth =
        FollowWaypoints(Pose2D(2.0, 2.0, 0.0), {{22, 2}, {22, 14}, {2, 14}, {2, 2}, {10, 2}}, path);
    const LaserSimulatorOptions laser = testing::RingBuildingLaser();
    std::mt19937 random(11);
    Drive d;
    const LineMap world = testing::RingBuilding();
    for (std::size_t i = 0; i < truth.size(); ++i) {
      d.scans.push_back(SimulateLaser(world, truth[i], laser, random));
      const Pose2D step = i == 0 ? Pose2D{} : Between(truth[i - 1], truth[i]);
      d.odometry.push_back(i == 0 ? truth[0]
                                  : d.odometry.back() * Pose2D(1.005 * step.x_m, 1.005 * step.y_m,
                                                               1.013 * step.yaw_rad));
    }
    return d;
  }();
  return drive;
}

class DriveSource : public IterationSource {
 public:
  explicit DriveSource(std::size_t scans) : scans_(std::min(scans, RingDrive().scans.size())) {}
  bool Next(Iteration& iteration) override {
    if (next_ >= scans_) return false;
    iteration = {};
    iteration.timestamp_s = 100.0 + 0.5 * static_cast<double>(next_);
    iteration.scan = RingDrive().scans[next_];
    iteration.odometry = RingDrive().odometry[next_];
    iteration.origin = "ring.log:" + std::to_string(next_ + 1);
    ++next_;
    return true;
  }
  LaserMounting mounting() const override { return {}; }
  double Progress() const override { return static_cast<double>(next_) / scans_; }

 private:
  std::size_t scans_, next_ = 0;
};

// A session with loop closure, tracking against every node or (tracking_path_m > 0) against the
// newest nodes only.
SessionFactory Factory(double tracking_path_m = 0.0) {
  return [tracking_path_m](const IterationSource& source) {
    SessionConfig config;
    config.session.initial_pose = {2.0, 2.0, 0.0};
    config.session.loop_closure.enabled = true;
    config.session.loop_closure.tracking_path_m = tracking_path_m;
    return std::make_unique<Session>(config, source.mounting(), LineMap{}, PointMap{});
  };
}

const nlohmann::json kIdentity = {{"command", "session"}, {"log", "ring.log"}};

// A whole run into `folder`: the session over `scans` scans (at most `max_scans`), then the files.
SessionRun RunInto(RunFolder& folder, std::size_t scans, std::size_t max_scans = 0,
                   double tracking_path_m = 0.0) {
  DriveSource source(scans);
  folder.Begin(kIdentity);
  SessionRunOptions options;
  options.progress = false;
  options.max_scans = max_scans;
  SessionRun run = RunSession(source, Factory(tracking_path_m), folder, options);
  folder.Correct(run.session->CorrectedPostures());
  folder.WriteGraph(*run.session->pose_graph());
  folder.Finish(run.session->point_map(), SummaryJson(run, source));
  return run;
}

// A record without its timings (`timings_ms`, every `time_s`): the only part two runs of the same
// work do not share.
void EraseTimings(nlohmann::json& value) {
  if (value.is_object()) {
    value.erase("timings_ms");
    value.erase("time_s");
  }
  if (value.is_structured())
    for (auto& item : value) EraseTimings(item);
}

std::string RecordsWithoutTimings(const std::string& path) {
  std::ifstream in(path);
  std::string line, out;
  while (std::getline(in, line)) {
    nlohmann::json record = nlohmann::json::parse(line);
    EraseTimings(record);
    out += record.dump() + "\n";
  }
  return out;
}

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

class SessionResumeTest : public testing::TemporaryDirTest {
 protected:
  // A run cut off after `cut` iterations with half a record after them, as a kill leaves it.
  void CutRun(const std::string& dir, std::size_t cut, double tracking_path_m = 0.0) {
    {
      RunFolder folder(dir);
      DriveSource source(RingDrive().scans.size());
      folder.Begin(kIdentity);
      SessionRunOptions options;
      options.progress = false;
      options.max_scans = cut;
      RunSession(source, Factory(tracking_path_m), folder, options);
    }
    std::ofstream(dir + "/iterations.jsonl", std::ios::app)
        << "{\"index\": " << cut << ", \"timestamp_s\": 1";
  }
};

TEST_F(SessionResumeTest, AResumedRunEndsWithTheFilesOfAnUninterruptedOne) {
  const std::size_t scans = RingDrive().scans.size();
  ASSERT_GT(scans, 120u);
  RunFolder whole(dir_ + "/whole");
  const SessionRun uninterrupted = RunInto(whole, scans);
  ASSERT_GT(uninterrupted.counts.closures_tried, 0u) << "the drive must try loop closures";

  CutRun(dir_ + "/cut", scans - 40);  // after some closures were tried
  RunFolder resumed_folder(dir_ + "/cut", RunFolderOpening::kResume);
  EXPECT_EQ(resumed_folder.recorded().size(), scans - 40);
  const SessionRun resumed = RunInto(resumed_folder, scans);

  EXPECT_EQ(resumed.counts.replayed, scans - 40);
  EXPECT_EQ(resumed.counts.iterations, uninterrupted.counts.iterations);
  EXPECT_EQ(resumed.counts.validated, uninterrupted.counts.validated);
  EXPECT_EQ(resumed.counts.inserted, uninterrupted.counts.inserted);
  EXPECT_EQ(resumed.counts.closures_tried, uninterrupted.counts.closures_tried);
  EXPECT_EQ(resumed.counts.closures_accepted, uninterrupted.counts.closures_accepted);
  for (const char* file :
       {"trajectory.tum", "trajectory-online.tum", "map.pcd", "graph.g2o", "run.json"})
    EXPECT_EQ(Bytes(dir_ + "/cut/" + file), Bytes(dir_ + "/whole/" + file)) << file;
  EXPECT_EQ(RecordsWithoutTimings(dir_ + "/cut/iterations.jsonl"),
            RecordsWithoutTimings(dir_ + "/whole/iterations.jsonl"));
}

// Tracking against the nodes of the last 10 m of path only: the map the scans were localised on
// slides along (and is rendered again on resuming as it was), and the map written is the whole.
TEST_F(SessionResumeTest, ARunTrackingItsNewestNodesResumesAndWritesTheWholeMap) {
  const std::size_t scans = RingDrive().scans.size();
  const double tracking_path_m = 10.0;
  RunFolder whole(dir_ + "/whole");
  const SessionRun uninterrupted = RunInto(whole, scans, 0, tracking_path_m);
  ASSERT_GT(uninterrupted.counts.closures_tried, 0u) << "the drive must try loop closures";
  const auto& session = static_cast<const Session&>(*uninterrupted.session);
  const PointMap every_node =
      session.loop_closer().Render(session.point_map().options(), MapExtensionOptions{}, 0, true);
  EXPECT_EQ(session.point_map().live_size(), every_node.live_size());
  std::size_t largest_tracked = 0;
  {
    std::ifstream in(dir_ + "/whole/iterations.jsonl");
    for (std::string line; std::getline(in, line);)
      largest_tracked =
          std::max(largest_tracked, nlohmann::json::parse(line)["map_points"].get<std::size_t>());
  }
  EXPECT_LT(largest_tracked, every_node.live_size() * 3 / 4)
      << "the map tracked against never held more than 20 m of the 70 m lap";

  CutRun(dir_ + "/cut", scans - 40, tracking_path_m);
  RunFolder resumed_folder(dir_ + "/cut", RunFolderOpening::kResume);
  const SessionRun resumed = RunInto(resumed_folder, scans, 0, tracking_path_m);
  EXPECT_EQ(resumed.counts.replayed, scans - 40);
  EXPECT_EQ(resumed.counts.closures_accepted, uninterrupted.counts.closures_accepted);
  for (const char* file : {"trajectory.tum", "map.pcd", "graph.g2o"})
    EXPECT_EQ(Bytes(dir_ + "/cut/" + file), Bytes(dir_ + "/whole/" + file)) << file;
  EXPECT_EQ(RecordsWithoutTimings(dir_ + "/cut/iterations.jsonl"),
            RecordsWithoutTimings(dir_ + "/whole/iterations.jsonl"));
}

TEST_F(SessionResumeTest, ARecordTheReplayDisagreesWithIsRefusedNamingItsLine) {
  CutRun(dir_ + "/cut", 30);
  // Line 12 says the scan did not extend the map (or the opposite): another log or version.
  const std::string path = dir_ + "/cut/iterations.jsonl";
  std::vector<std::string> lines;
  {
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  nlohmann::json record = nlohmann::json::parse(lines[11]);
  record["map_points"] = record["map_points"].get<std::size_t>() + 1;
  lines[11] = record.dump();
  lines.pop_back();  // the half record
  {
    std::ofstream out(path, std::ios::trunc);
    for (const std::string& line : lines) out << line << "\n";
  }
  const std::string before = Bytes(path);
  RunFolder folder(dir_ + "/cut", RunFolderOpening::kResume);
  DriveSource source(RingDrive().scans.size());
  folder.Begin(kIdentity);
  SessionRunOptions options;
  options.progress = false;
  try {
    RunSession(source, Factory(), folder, options);
    FAIL() << "the mismatch was not noticed";
  } catch (const ReplayMismatch& e) {
    EXPECT_TRUE(testing::Contains(e.what(), "iterations.jsonl:12: cannot resume: map_points"))
        << e.what();
  }
  EXPECT_EQ(Bytes(path), before);
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/cut/trajectory.tum"));
}

TEST_F(SessionResumeTest, ALogShorterThanTheRecordsIsRefused) {
  CutRun(dir_ + "/cut", 30);
  RunFolder folder(dir_ + "/cut", RunFolderOpening::kResume);
  DriveSource source(20);
  folder.Begin(kIdentity);
  SessionRunOptions options;
  options.progress = false;
  try {
    RunSession(source, Factory(), folder, options);
    FAIL() << "a log shorter than the records was resumed";
  } catch (const ReplayMismatch& e) {
    EXPECT_TRUE(testing::Contains(e.what(), "ended (or --max-scans stopped it) after 20 scans"))
        << e.what();
    EXPECT_TRUE(testing::Contains(e.what(), "holds 30 records")) << e.what();
  }
}

TEST_F(SessionResumeTest, AnotherIdentityIsRefusedNamingWhatDiffers) {
  CutRun(dir_ + "/cut", 10);
  RunFolder folder(dir_ + "/cut", RunFolderOpening::kResume);
  try {
    folder.Begin({{"command", "session"}, {"log", "other.log"}});
    FAIL() << "another log was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(testing::Contains(e.what(), "/log")) << e.what();
    EXPECT_TRUE(testing::Contains(e.what(), "run.json")) << e.what();
  }
}

TEST_F(SessionResumeTest, OnlyTheIncompleteLastLineIsCutOffAndABrokenRecordIsAParseError) {
  CutRun(dir_ + "/cut", 10);
  const std::string path = dir_ + "/cut/iterations.jsonl";
  const RecordedRun read = ReadRecordsToResume(path);
  EXPECT_EQ(read.iterations.size(), 10u);
  EXPECT_TRUE(read.partial_line);
  { RunFolder folder(dir_ + "/cut", RunFolderOpening::kResume); }
  EXPECT_EQ(std::filesystem::file_size(path), read.complete_bytes);
  EXPECT_FALSE(ReadRecordsToResume(path).partial_line);
  std::ofstream(path, std::ios::app) << "{\"index\": 10}\n";
  testing::ExpectParseError([&] { ReadRecordsToResume(path); }, path, 11,
                            "expected an iteration record");
}

TEST_F(SessionResumeTest, AFolderWithoutRecordsHasNothingToResume) {
  std::filesystem::create_directories(dir_ + "/empty");
  try {
    RunFolder folder(dir_ + "/empty", RunFolderOpening::kResume);
    FAIL() << "an empty folder was resumed";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(testing::Contains(e.what(), "there is no run to resume")) << e.what();
  }
}

TEST_F(SessionResumeTest, OverwritingRemovesTheEarlierRunsFilesBeforeAnythingIsRecorded) {
  RunFolder first(dir_ + "/run");
  RunInto(first, 15);
  ASSERT_TRUE(std::filesystem::exists(dir_ + "/run/summary.json"));
  testing::WriteText(dir_ + "/run/notes.txt", "mine");
  RunFolder again(dir_ + "/run", /*overwrite=*/true);
  for (const char* file : {"summary.json", "map.pcd", "trajectory.tum", "graph.g2o", "run.json",
                           "trajectory-online.tum"})
    EXPECT_FALSE(std::filesystem::exists(dir_ + "/run/" + file)) << file;
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/run/notes.txt"));  // not a run's file
}

}  // namespace
}  // namespace scanloc
