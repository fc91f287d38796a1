// `scanloc session --resume`: the classroom session stopped part way (by --max-scans, with half a
// record after it as a kill leaves) and resumed ends with the uninterrupted run's files; resuming
// with other options, or into a folder that holds no run, is refused and changes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

class ResumeCliTest : public testing::TemporaryDirTest {
 protected:
  std::vector<std::string> Session(const std::string& out, std::vector<std::string> extra = {}) {
    const std::string classroom = std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/";
    std::vector<std::string> words = {"session",
                                      "--log",
                                      classroom + "classroom.seq.jsonl",
                                      "--line-map",
                                      classroom + "classroom.lines",
                                      "--initial-pose",
                                      "1.126",
                                      "3.112",
                                      "0.0463",
                                      "--set",
                                      "loop_closure.enabled=true",
                                      "--out",
                                      dir_ + "/" + out,
                                      "--quiet"};
    words.insert(words.end(), extra.begin(), extra.end());
    return words;
  }
  std::string File(const std::string& run, const std::string& name) const {
    return testing::ReadWholeFile(dir_ + "/" + run + "/" + name);
  }
};

// The summary without what differs between two runs of the same work (time, memory) and the
// resume's own count.
nlohmann::json Comparable(nlohmann::json summary) {
  for (const char* key : {"wall_time_s", "scans_per_s", "times_real_time", "peak_resident_mb",
                          "cpu_time_s", "times_real_time_on_cpu", "resumed_after_records",
                          "map_signature_wall_s", "final_match_wall_s"})
    summary.erase(key);
  summary["inputs"].erase("log");  // absolute paths: the same here
  return summary;
}

TEST_F(ResumeCliTest, AStoppedSessionResumedEndsWithTheUninterruptedRunsFiles) {
  const auto whole = testing::RunScanloc(Session("whole"), dir_);
  ASSERT_TRUE(whole.exited && whole.exit_code == 0) << whole;
  const auto stopped = testing::RunScanloc(Session("cut", {"--max-scans", "9"}), dir_);
  ASSERT_TRUE(stopped.exited && stopped.exit_code == 0) << stopped;
  std::ofstream(dir_ + "/cut/iterations.jsonl", std::ios::app) << "{\"index\": 9, \"timest";
  const auto resumed = testing::RunScanloc(Session("cut", {"--resume"}), dir_);
  ASSERT_TRUE(resumed.exited && resumed.exit_code == 0) << resumed;
  EXPECT_TRUE(testing::Contains(resumed.err, "replaying 9 recorded iterations")) << resumed;

  for (const char* file : {"trajectory.tum", "trajectory-online.tum", "map.pcd", "graph.g2o"})
    EXPECT_EQ(File("cut", file), File("whole", file)) << file;
  const auto summary = nlohmann::json::parse(File("cut", "summary.json"));
  EXPECT_EQ(summary["resumed_after_records"], 9);
  EXPECT_EQ(Comparable(summary), Comparable(nlohmann::json::parse(File("whole", "summary.json"))));
}

TEST_F(ResumeCliTest, ResumingWithOtherOptionsIsRefusedAndChangesNothing) {
  const auto stopped = testing::RunScanloc(Session("cut", {"--max-scans", "5"}), dir_);
  ASSERT_TRUE(stopped.exited && stopped.exit_code == 0) << stopped;
  const std::string records = File("cut", "iterations.jsonl");
  const std::string summary = File("cut", "summary.json");
  const auto other = testing::RunScanloc(
      Session("cut", {"--resume", "--set", "session.insert_translation_m=0.3"}), dir_);
  ASSERT_TRUE(other.exited && other.exit_code != 0) << other;
  EXPECT_TRUE(testing::Contains(other.err, "/config/session/insert_translation_m")) << other;
  EXPECT_EQ(File("cut", "iterations.jsonl"), records);
  EXPECT_EQ(File("cut", "summary.json"), summary);
}

TEST_F(ResumeCliTest, ResumingAFolderWithoutARunIsRefused) {
  std::filesystem::create_directories(dir_ + "/nothing");
  const auto run = testing::RunScanloc(Session("nothing", {"--resume"}), dir_);
  ASSERT_TRUE(run.exited && run.exit_code != 0) << run;
  EXPECT_TRUE(testing::Contains(run.err, "there is no run to resume")) << run;
  const auto forced = testing::RunScanloc(Session("nothing", {"--resume", "--force"}), dir_);
  ASSERT_TRUE(forced.exited && forced.exit_code != 0) << forced;
  EXPECT_TRUE(testing::Contains(forced.err, "--resume and --force exclude each other")) << forced;
}

}  // namespace
}  // namespace scanloc
