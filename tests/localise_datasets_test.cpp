// `scanloc localise` on a map a default session built of ACES (../shared/datasets): a robot
// carried elsewhere must be found again (the localise issue's kidnapping target, as
// scripts/localise-benchmark.sh measures it). Skips when the logs are absent (in CI they are
// present).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "scanloc/io/trajectory.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

class LocaliseOnAcesMap : public testing::TemporaryDirTest {};

std::vector<nlohmann::json> Records(const std::string& run) {
  std::vector<nlohmann::json> records;
  std::ifstream in(run + "/iterations.jsonl");
  for (std::string line; std::getline(in, line);) records.push_back(nlohmann::json::parse(line));
  return records;
}

// Measured 2026-12-02 (scripts/localise-benchmark.sh): confirmed again 13 scans after the carry
// on the default map, 10–14 on the ten maps of the robustness harness's perturbations (87 on the
// default map, 4 of 10 within 30, with rule 2's bound the same at every place).
TEST_F(LocaliseOnAcesMap, ARobotCarriedElsewhereIsConfirmedAgainWithin30ScansOfTheCarry) {
  SCANLOC_REQUIRE_DATASETS(datasets);
  const std::string log = datasets + "/aces.clf.gz";
  const auto session =
      testing::RunScanloc({"session", "--log", log, "--out", dir_ + "/map", "--quiet"}, dir_);
  ASSERT_TRUE(session.exited && session.exit_code == 0) << session;
  std::ifstream summary_file(dir_ + "/map/summary.json");
  const auto summary = nlohmann::json::parse(summary_file);
  const int scans = summary["iterations"].get<int>();
  // The benchmark's splice: 200 scans from 1/7 of the log, then 200 from 4/7.
  const auto splice = testing::RunCommand(
      {"python3", std::string(SCANLOC_SOURCE_DIR) + "/scripts/splice-carmen.py", log,
       std::to_string(scans / 7), std::to_string(scans * 4 / 7), "200"},
      dir_);
  ASSERT_TRUE(splice.exited && splice.exit_code == 0) << splice.err;
  std::ofstream(dir_ + "/splice.clf") << splice.out;
  const auto localise = testing::RunScanloc({"localise", "--point-map", dir_ + "/map/map.pcd",
                                             "--log", dir_ + "/splice.clf", "--out",
                                             dir_ + "/run", "--quiet"},
                                            dir_);
  ASSERT_TRUE(localise.exited && localise.exit_code == 0) << localise;
  const std::vector<nlohmann::json> records = Records(dir_ + "/run");
  ASSERT_EQ(records.size(), 400u);
  int lost_at = -1, reconfirmed_at = -1;
  for (const auto& r : records) {
    const int i = r["index"].get<int>();
    if (i >= 200 && lost_at < 0 && r.value("lost", false)) lost_at = i;
    if (lost_at >= 0 && reconfirmed_at < 0 && r["state"] == "confirmed") reconfirmed_at = i;
  }
  ASSERT_GE(lost_at, 200) << "the carry was never noticed";
  EXPECT_LE(lost_at, 210);
  ASSERT_GE(reconfirmed_at, 0) << "the second place was never confirmed";
  EXPECT_LE(reconfirmed_at - 200, 30);
  // From there on the postures are the mapping session's (matched by timestamp).
  std::map<long long, Pose2D> reference;
  for (const StampedPose& p : ReadTumTrajectory(dir_ + "/map/trajectory.tum"))
    reference[std::llround(p.timestamp_s * 1e6)] = p.pose;
  std::vector<double> errors;
  for (const auto& r : records) {
    if (r["index"].get<int>() < reconfirmed_at) continue;
    const auto found = reference.find(std::llround(r["timestamp_s"].get<double>() * 1e6));
    ASSERT_NE(found, reference.end()) << "scan " << r["index"];
    const auto& p = r["T_world_robot"];
    errors.push_back(std::hypot(p["x_m"].get<double>() - found->second.x_m,
                                p["y_m"].get<double>() - found->second.y_m));
  }
  ASSERT_FALSE(errors.empty());
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.05) << "median";
  EXPECT_LT(errors[errors.size() * 95 / 100], 0.3) << "95th percentile";
}

}  // namespace
}  // namespace scanloc
