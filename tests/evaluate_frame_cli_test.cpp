// `scanloc evaluate` scores a session's trajectory (the robot's postures) on relations between
// scans through the laser's mounting: the run's, read from summary.json beside the trajectory, or
// the one given with --mounting. A robot passing a place east then west with its laser 0.04 m
// ahead: the scans' relation is 0.08 m and a half turn, the robot's postures coincide.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "run_scanloc.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

constexpr double kTolerance = 1e-6;

class EvaluateFrameCliTest : public testing::TemporaryDirTest {
 protected:
  void SetUp() override {
    TemporaryDirTest::SetUp();
    std::filesystem::create_directories(dir_ + "/run");
    // TUM: t x y z qx qy qz qw; the second posture turned by π.
    trajectory_ = Write("run/trajectory.tum", "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 1 0\n");
    relations_ = Write("scans.relations", "1.0 2.0 -0.08 0 0 0 0 3.141592653589793\n");
  }
  void WriteSummary(double laser_x_m) {
    Write("run/summary.json",
          nlohmann::json{
              {"config", {{"mounting", {{"x_m", laser_x_m}, {"y_m", 0.0}, {"yaw_rad", 0.0}}}}}}
              .dump());
  }
  nlohmann::json Evaluate(std::vector<std::string> extra = {}) {
    std::vector<std::string> arguments = {"evaluate",    "--trajectory", trajectory_,
                                          "--relations", relations_,     "--json"};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    last_ = testing::RunScanloc(arguments, dir_);
    EXPECT_TRUE(last_.exited && last_.exit_code == 0) << last_;
    return nlohmann::json::parse(last_.out);
  }
  std::string trajectory_, relations_;
  testing::ScanlocRun last_;
};

TEST_F(EvaluateFrameCliTest, TheRunsMountingFromSummaryJsonMakesTheScansRelationExact) {
  WriteSummary(0.04);
  const nlohmann::json metric = Evaluate();
  EXPECT_EQ(metric["matched"], 1);
  EXPECT_NEAR(metric["translation_m"]["mean"].get<double>(), 0.0, kTolerance);
  EXPECT_NEAR(metric["laser_mounting"]["x_m"].get<double>(), 0.04, kTolerance);
  EXPECT_NE(metric["laser_mounting"]["source"].get<std::string>().find("summary.json"),
            std::string::npos);
}

TEST_F(EvaluateFrameCliTest, AGivenMountingOverridesTheRunsAndNoMountingScoresTheRobotsPostures) {
  WriteSummary(0.04);
  const nlohmann::json robot = Evaluate({"--mounting", "0", "0", "0"});
  EXPECT_NEAR(robot["translation_m"]["mean"].get<double>(), 0.08, kTolerance);
  EXPECT_EQ(robot["laser_mounting"]["source"], "given with --mounting");
  std::filesystem::remove(dir_ + "/run/summary.json");
  const nlohmann::json unknown = Evaluate();
  EXPECT_NEAR(unknown["translation_m"]["mean"].get<double>(), 0.08, kTolerance);
  EXPECT_NE(last_.err.find("records no laser mounting"), std::string::npos) << last_;
}

TEST_F(EvaluateFrameCliTest, AnUnreadableSummaryOrAMountingOfTwoNumbersOrNotFiniteFailsSayingWhy) {
  Write("run/summary.json", "{\"config\": {\"mounting\": {\"x_m\": \"ahead\"}}}");
  testing::ScanlocRun r = testing::RunScanloc(
      {"evaluate", "--trajectory", trajectory_, "--relations", relations_}, dir_);
  EXPECT_TRUE(r.exited && r.exit_code != 0) << r;
  EXPECT_NE(r.err.find("summary.json"), std::string::npos) << r;
  EXPECT_NE(r.err.find("config.mounting"), std::string::npos) << r;
  r = testing::RunScanloc({"evaluate", "--trajectory", trajectory_, "--relations", relations_,
                           "--mounting", "0.04", "0"},
                          dir_);
  EXPECT_TRUE(r.exited && r.exit_code != 0) << r;
  EXPECT_NE(r.err.find("mounting"), std::string::npos) << r;
  r = testing::RunScanloc({"evaluate", "--trajectory", trajectory_, "--relations", relations_,
                           "--mounting", "0.04", "nan", "0"},
                          dir_);
  EXPECT_TRUE(r.exited && r.exit_code != 0) << r;
  EXPECT_NE(r.err.find("finite"), std::string::npos) << r;
}

}  // namespace
}  // namespace scanloc
