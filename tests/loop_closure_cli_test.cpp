// `scanloc session` with loop closure on: the run folder holds the pose graph (g2o, read back),
// the trajectory as the session gave it beside the corrected one, and the closure counts.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "run_scanloc.hpp"
#include "scanloc/io/g2o_file.hpp"
#include "scanloc/io/trajectory.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

class LoopClosureCliTest : public testing::TemporaryDirTest {};

TEST_F(LoopClosureCliTest, ASessionWithLoopClosureWritesItsGraphAndBothTrajectories) {
  const std::string classroom = std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/";
  const auto run = testing::RunScanloc(
      {"session", "--log", classroom + "classroom.seq.jsonl", "--line-map",
       classroom + "classroom.lines", "--initial-pose", "1.126", "3.112", "0.0463", "--set",
       "loop_closure.enabled=true", "--out", dir_ + "/run", "--quiet"},
      dir_);
  ASSERT_TRUE(run.exited && run.exit_code == 0) << run;
  const auto summary = nlohmann::json::parse(testing::ReadWholeFile(dir_ + "/run/summary.json"));
  ASSERT_TRUE(summary.contains("loop_closure")) << summary.dump(2);
  const PoseGraph graph = ReadG2o(dir_ + "/run/graph.g2o");
  // Every scan that extended the map is a node, linked to the one before.
  EXPECT_EQ(graph.nodes().size(), summary["inserted"].get<std::size_t>());
  EXPECT_EQ(graph.nodes().size(), summary["loop_closure"]["nodes"].get<std::size_t>());
  EXPECT_GE(graph.edges().size() + 1, graph.nodes().size());
  EXPECT_EQ(summary["files"]["pose_graph"], "graph.g2o");
  const auto online = ReadTumTrajectory(dir_ + "/run/trajectory-online.tum");
  const auto corrected = ReadTumTrajectory(dir_ + "/run/trajectory.tum");
  EXPECT_EQ(online.size(), corrected.size());
  EXPECT_EQ(online.size(), summary["iterations"].get<std::size_t>());
}

}  // namespace
}  // namespace scanloc
