// `scanloc localise` on a map a default session built of ACES (../shared/datasets): the
// benchmark's three starts must agree with the mapping session and a robot carried elsewhere must
// be found again (the localise issue's targets, as scripts/localise-benchmark.sh measures them).
// Skips when the logs are absent (in CI they are present).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "scanloc/io/trajectory.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

// One default session's map of ACES, built once for the suite (about 5 s) into its own folder.
class LocaliseOnAcesMap : public testing::TemporaryDirTest {
 protected:
  static void SetUpTestSuite() {
    const std::string datasets = testing::DatasetsDir();
    if (datasets.empty()) return;
    map_root_ = testing::TemporaryDir();
    const auto session = testing::RunScanloc(
        {"session", "--log", datasets + "/aces.clf.gz", "--out", map_root_ + "/map", "--quiet"},
        map_root_);
    if (!session.exited || session.exit_code != 0) return;
    std::ifstream summary_file(map_root_ + "/map/summary.json");
    scans_ = nlohmann::json::parse(summary_file)["iterations"].get<int>();
  }
  static void TearDownTestSuite() {
    if (!map_root_.empty()) std::filesystem::remove_all(map_root_);
  }
  static std::string MapDir() { return map_root_ + "/map"; }
  static inline std::string map_root_;
  static inline int scans_ = 0;  // 0 when the session failed
};

std::vector<nlohmann::json> Records(const std::string& run) {
  std::vector<nlohmann::json> records;
  std::ifstream in(run + "/iterations.jsonl");
  for (std::string line; std::getline(in, line);) records.push_back(nlohmann::json::parse(line));
  return records;
}

// The mapping session's postures by timestamp (µs).
std::map<long long, Pose2D> SessionPostures(const std::string& map_dir) {
  std::map<long long, Pose2D> reference;
  for (const StampedPose& p : ReadTumTrajectory(map_dir + "/trajectory.tum"))
    reference[std::llround(p.timestamp_s * 1e6)] = p.pose;
  return reference;
}

// The distance of a record's posture from the session's posture of the same scan (matched by
// timestamp); none for a scan the session did not pose.
std::optional<double> DistanceFromTheSession(const nlohmann::json& r,
                                             const std::map<long long, Pose2D>& reference) {
  const auto found = reference.find(std::llround(r["timestamp_s"].get<double>() * 1e6));
  if (found == reference.end()) return std::nullopt;
  const auto& p = r["T_world_robot"];
  return std::hypot(p["x_m"].get<double>() - found->second.x_m,
                    p["y_m"].get<double>() - found->second.y_m);
}

// The distances of the records from scan `from` on, sorted.
std::vector<double> DistancesFromTheSession(const std::vector<nlohmann::json>& records,
                                            const std::string& map_dir, int from) {
  const std::map<long long, Pose2D> reference = SessionPostures(map_dir);
  std::vector<double> errors;
  for (const auto& r : records)
    if (r["index"].get<int>() >= from)
      if (const std::optional<double> d = DistanceFromTheSession(r, reference))
        errors.push_back(*d);
  std::sort(errors.begin(), errors.end());
  return errors;
}

// How many records state "confirmed" at a posture more than `far_m` from the session's posture
// of the same scan.
int ConfirmedFarFromTheSession(const std::vector<nlohmann::json>& records,
                               const std::string& map_dir, double far_m) {
  const std::map<long long, Pose2D> reference = SessionPostures(map_dir);
  int far = 0;
  for (const auto& r : records) {
    if (r["state"] != "confirmed") continue;
    const std::optional<double> d = DistanceFromTheSession(r, reference);
    far += d && *d > far_m;
  }
  return far;
}

// Measured 2026-12-02 (scripts/localise-benchmark.sh): all three agree, first confirmed at scans
// 12, 17 and 36. Before the saved map was carved by earlier scans, aces-5267 confirmed a place
// 4–19 m off (five points the session's last scans laid hid the rotunda ahead); before a place
// could be outmatched, aces-1053 stayed ambiguous among alike corridors until scan 106. Since
// 2026-12-06 only a new view's costs are evidence (localise.evidence_from_new_views): confirmed
// at scans 128, 14 and 206, and no scan is confirmed more than 1 m from the session (on 4 of the
// robustness harness's 30 ACES starts a wrong place was confirmed before: docs/BENCHMARKS.md).
TEST_F(LocaliseOnAcesMap, TheBenchmarksThreeStartsAgreeWithTheMappingSessionAfter30Scans) {
  SCANLOC_REQUIRE_DATASETS(datasets);
  ASSERT_GT(scans_, 0) << "the mapping session failed";
  for (const int k : {1, 3, 5}) {
    const std::string start = std::to_string(scans_ * k / 7), run = dir_ + "/start-" + start;
    const auto localise = testing::RunScanloc(
        {"localise", "--point-map", MapDir() + "/map.pcd", "--log", datasets + "/aces.clf.gz",
         "--skip-scans", start, "--max-scans", "400", "--out", run, "--quiet"},
        dir_);
    ASSERT_TRUE(localise.exited && localise.exit_code == 0) << localise;
    const std::vector<double> errors =
        DistancesFromTheSession(Records(run), MapDir(), 30);  // indices count from the start
    ASSERT_GT(errors.size(), 300u) << "start " << start;
    EXPECT_LT(errors[errors.size() / 2], 0.10) << "median, start " << start;
    EXPECT_LT(errors[errors.size() * 95 / 100], 0.30) << "95th percentile, start " << start;
    EXPECT_EQ(ConfirmedFarFromTheSession(Records(run), MapDir(), 1.0), 0) << "start " << start;
  }
}

// The same three starts on a copy of the log whose pose fields are all zero (a log whose odometry
// was never filled in): the odometry is set aside once the ranges move, and each scan's match on
// the scan before carries the hypotheses instead. Measured 2026-12-06: confirmed at scans 14, 18
// and 25 of each start, 95th percentiles 0.048, 0.049 and 0.039 m. Before, localise believed the
// odometry standing still and confirmed no posture at all (it said so).
TEST_F(LocaliseOnAcesMap, TheThreeStartsWithThePoseFieldsZeroedAgreeWithTheMappingSession) {
  SCANLOC_REQUIRE_DATASETS(datasets);
  ASSERT_GT(scans_, 0) << "the mapping session failed";
  const std::string zeroed = dir_ + "/aces-zeroed.clf.gz";
  testing::WriteWithZeroedOdometry("aces", zeroed);
  for (const int k : {1, 3, 5}) {
    const std::string start = std::to_string(scans_ * k / 7), run = dir_ + "/start-" + start;
    const auto localise =
        testing::RunScanloc({"localise", "--point-map", MapDir() + "/map.pcd", "--log", zeroed,
                             "--skip-scans", start, "--max-scans", "400", "--out", run, "--quiet"},
                            dir_);
    ASSERT_TRUE(localise.exited && localise.exit_code == 0) << localise;
    EXPECT_TRUE(testing::Contains(localise.out, "of them moved by their match on the scan before"))
        << localise.out;
    EXPECT_TRUE(testing::Contains(localise.err, "the log's odometry had not moved"))
        << localise.err;
    const std::vector<nlohmann::json> records = Records(run);
    const auto confirmed = std::find_if(records.begin(), records.end(),
                                        [](const auto& r) { return r["state"] == "confirmed"; });
    ASSERT_NE(confirmed, records.end()) << "never confirmed, start " << start;
    EXPECT_LE((*confirmed)["index"].get<int>(), 60) << "start " << start;
    const std::vector<double> errors = DistancesFromTheSession(records, MapDir(), 30);
    ASSERT_GT(errors.size(), 300u) << "start " << start;
    EXPECT_LT(errors[errors.size() / 2], 0.05) << "median, start " << start;
    EXPECT_LT(errors[errors.size() * 95 / 100], 0.15) << "95th percentile, start " << start;
  }
}

// Measured 2026-12-02 (scripts/localise-benchmark.sh): confirmed again 13 scans after the carry
// on the default map, 10–14 on the ten maps of the robustness harness's perturbations (87 on the
// default map, 4 of 10 within 30, with rule 2's bound the same at every place). Measured again
// 2026-12-05 on the ten maps of today's harness: 10–13 scans on seven of them, 77–88 on three
// (80–92 on three once a session keeps its cheapest refinement as the unconfirmed guess, the
// default map among them). Which maps take long changes with the map, not with the localiser.
TEST_F(LocaliseOnAcesMap, ARobotCarriedElsewhereIsConfirmedAgainWithin100ScansOfTheCarry) {
  SCANLOC_REQUIRE_DATASETS(datasets);
  ASSERT_GT(scans_, 0) << "the mapping session failed";
  const std::string log = datasets + "/aces.clf.gz";
  const int scans = scans_;
  // The benchmark's splice: 200 scans from 1/7 of the log, then 200 from 4/7.
  const auto splice =
      testing::RunCommand({"python3", std::string(SCANLOC_SOURCE_DIR) + "/scripts/splice-carmen.py",
                           log, std::to_string(scans / 7), std::to_string(scans * 4 / 7), "200"},
                          dir_);
  ASSERT_TRUE(splice.exited && splice.exit_code == 0) << splice.err;
  std::ofstream(dir_ + "/splice.clf") << splice.out;
  const auto localise =
      testing::RunScanloc({"localise", "--point-map", MapDir() + "/map.pcd", "--log",
                           dir_ + "/splice.clf", "--out", dir_ + "/run", "--quiet"},
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
  EXPECT_LE(reconfirmed_at - 200, 100);
  // From there on the postures are the mapping session's.
  const std::vector<double> errors = DistancesFromTheSession(records, MapDir(), reconfirmed_at);
  ASSERT_GT(errors.size(), static_cast<std::size_t>(400 - reconfirmed_at) * 9 / 10);
  EXPECT_LT(errors[errors.size() / 2], 0.05) << "median";
  EXPECT_LT(errors[errors.size() * 95 / 100], 0.3) << "95th percentile";
}

// The robustness harness's perturbations of the defaults (scripts/perturbations.txt: "default" or
// one section.key=value a line), which scripts/robustness-sessions.sh runs too.
std::vector<std::string> HarnessPerturbations() {
  std::ifstream in(std::string(SCANLOC_SOURCE_DIR) + "/scripts/perturbations.txt");
  std::vector<std::string> perturbations;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) perturbations.push_back(line);
  return perturbations;
}

class LocaliseOnHarnessMaps : public testing::TemporaryDirTest {};

// The ten ACES maps the robustness harness's sessions write, each localised from the benchmark's
// three starts (scripts/localise-robustness.sh does the same with Intel beside). Measured
// 2026-12-06: 26 of the 30 starts agree with the session that wrote their map, and no scan is
// confirmed more than 1 m from it. Before a scan's costs counted only at a new view
// (localise.evidence_from_new_views), four starts confirmed places 7–47 m off (89–368 scans).
TEST_F(LocaliseOnHarnessMaps, NoStartOnTheTenAcesMapsConfirmsAPlaceAMetreOff) {
  SCANLOC_REQUIRE_DATASETS(datasets);
  const std::vector<std::string> perturbations = HarnessPerturbations();
  ASSERT_EQ(perturbations.size(), 10u) << "scripts/perturbations.txt";
  int starts = 0, agree = 0;
  for (std::size_t i = 0; i < perturbations.size(); ++i) {
    const std::string map = dir_ + "/map-p" + std::to_string(i);
    std::vector<std::string> args{"session", "--log", datasets + "/aces.clf.gz",
                                  "--out",   map,     "--quiet"};
    if (perturbations[i] != "default") args.insert(args.end(), {"--set", perturbations[i]});
    const auto session = testing::RunScanloc(args, dir_);
    ASSERT_TRUE(session.exited && session.exit_code == 0) << session;
    std::ifstream summary(map + "/summary.json");
    const int scans = nlohmann::json::parse(summary)["iterations"].get<int>();
    for (const int k : {1, 3, 5}) {
      const std::string start = std::to_string(scans * k / 7), run = map + "-" + start;
      const auto localise = testing::RunScanloc(
          {"localise", "--point-map", map + "/map.pcd", "--log", datasets + "/aces.clf.gz",
           "--skip-scans", start, "--max-scans", "400", "--out", run, "--quiet"},
          dir_);
      ASSERT_TRUE(localise.exited && localise.exit_code == 0) << localise;
      const std::vector<nlohmann::json> records = Records(run);
      EXPECT_EQ(ConfirmedFarFromTheSession(records, map, 1.0), 0)
          << perturbations[i] << ", start " << start;
      const std::vector<double> errors = DistancesFromTheSession(records, map, 30);
      ++starts;
      agree += errors.size() > 300u && errors[errors.size() / 2] < 0.10 &&
               errors[errors.size() * 95 / 100] < 0.30;
      std::filesystem::remove_all(run);
    }
    std::filesystem::remove_all(map);
  }
  EXPECT_GE(agree, 25) << "of " << starts << " starts agree";  // 26 measured
}

}  // namespace
}  // namespace scanloc
