// `scanloc localise` on the shipped classroom: from no initial posture it holds the room's two
// look-alike postures (the chapter's small-map ambiguity, Figure 6) until the scans tell them
// apart, then follows the posture a session started at the known one keeps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

std::vector<std::vector<double>> ReadTum(const std::string& path) {
  std::istringstream in(testing::ReadWholeFile(path));
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> row(8);
    for (double& v : row) fields >> v;
    rows.push_back(row);
  }
  return rows;
}

class LocaliseCliTest : public testing::TemporaryDirTest {
 protected:
  std::string Classroom(const std::string& file) const {
    return std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/" + file;
  }
  void CopySessionMapWithoutItsSummary();
};

TEST_F(LocaliseCliTest, FromNoPostureTheClassroomIsAmbiguousThenFollowsTheSessionWithin2cm) {
  const auto session =
      testing::RunScanloc({"session", "--log", Classroom("classroom.seq.jsonl"), "--line-map",
                           Classroom("classroom.lines"), "--initial-pose", "1.126", "3.112",
                           "0.0463", "--out", dir_ + "/session", "--quiet"},
                          dir_);
  ASSERT_TRUE(session.exited && session.exit_code == 0) << session;
  const auto localise =
      testing::RunScanloc({"localise", "--log", Classroom("classroom.seq.jsonl"), "--line-map",
                           Classroom("classroom.lines"), "--out", dir_ + "/localise", "--quiet"},
                          dir_);
  ASSERT_TRUE(localise.exited && localise.exit_code == 0) << localise;
  EXPECT_NE(localise.out.find("localise: posture confirmed at scan"), std::string::npos)
      << localise;
  const auto summary =
      nlohmann::json::parse(testing::ReadWholeFile(dir_ + "/localise/summary.json"));
  ASSERT_TRUE(summary["first_confirmed_scan"].is_number()) << summary.dump(2);
  const std::size_t confirmed = summary["first_confirmed_scan"].get<std::size_t>();
  EXPECT_GE(summary["max_hypotheses"].get<int>(), 2);  // the room turned half a turn
  // Both held until the paired costs told them apart (hypothesis_evidence.hpp): 6 scans.
  EXPECT_GE(summary["ambiguous_scans"].get<int>(), 3);
  // Over time: from the first scan, changes only, the confirmation among them.
  const auto& series = summary["hypotheses_over_time"];
  ASSERT_GE(series.size(), 2u) << summary.dump(2);
  EXPECT_EQ(series.front()["scan"], 0);
  bool confirmation_listed = false;
  for (std::size_t i = 1; i < series.size(); ++i) {
    EXPECT_LT(series[i - 1]["scan"].get<int>(), series[i]["scan"].get<int>());
    EXPECT_TRUE(series[i - 1]["state"] != series[i]["state"] ||
                series[i - 1]["hypotheses"] != series[i]["hypotheses"]);
    confirmation_listed =
        confirmation_listed ||
        (series[i]["state"] == "confirmed" && series[i]["scan"].get<std::size_t>() == confirmed);
  }
  EXPECT_TRUE(confirmation_listed) << series.dump();
  // Where the look-alike went, the series says why: out-costed at the same scans.
  bool reason_given = false;
  for (const auto& point : series)
    for (const auto& why : point.value("discarded", nlohmann::json::array()))
      reason_given =
          reason_given || why.get<std::string>().find("% more than") != std::string::npos;
  EXPECT_TRUE(reason_given) << series.dump();
  const auto reference = ReadTum(dir_ + "/session/trajectory.tum");
  const auto found = ReadTum(dir_ + "/localise/trajectory.tum");
  ASSERT_EQ(found.size(), reference.size());
  for (std::size_t i = confirmed; i < found.size(); ++i)
    EXPECT_LT(std::hypot(found[i][1] - reference[i][1], found[i][2] - reference[i][2]), 0.02)
        << "scan " << i;
  // The report tells the ambiguity and when it ended.
  const auto report = testing::RunScanloc({"report", dir_ + "/localise"}, dir_);
  ASSERT_TRUE(report.exited && report.exit_code == 0) << report;
  const std::string page = testing::ReadWholeFile(dir_ + "/localise/report.html");
  EXPECT_TRUE(testing::Contains(page, "ambiguous (2 hypotheses)"));
  EXPECT_TRUE(testing::Contains(page, "scan 0: ambiguous (2) → scan "))
      << "the summary table's hypotheses over time";
  EXPECT_TRUE(testing::Contains(page, "→ scan " + std::to_string(confirmed) + ": confirmed (1)"));
  EXPECT_TRUE(testing::Contains(page, "[discarded ("));
  EXPECT_TRUE(testing::Contains(page, "first confirmed scan</th><td>" + std::to_string(confirmed)));
}

TEST_F(LocaliseCliTest,
       CompareSetsALocaliseRunBesideTheSessionWithTheDistanceBetweenTheirPostures) {
  const std::vector<std::string> common{"--log",      Classroom("classroom.seq.jsonl"),
                                        "--line-map", Classroom("classroom.lines"),
                                        "--quiet",    "--out"};
  auto words = [&](const std::string& command, const std::string& out) {
    std::vector<std::string> w{command};
    w.insert(w.end(), common.begin(), common.end());
    w.push_back(dir_ + "/" + out);
    return w;
  };
  std::vector<std::string> session = words("session", "session");
  session.insert(session.end(), {"--initial-pose", "1.126", "3.112", "0.0463"});
  ASSERT_EQ(testing::RunScanloc(session, dir_).exit_code, 0);
  ASSERT_EQ(testing::RunScanloc(words("localise", "localise"), dir_).exit_code, 0);
  const auto compare =
      testing::RunScanloc({"compare", "--runs", dir_ + "/session", dir_ + "/localise"}, dir_);
  ASSERT_TRUE(compare.exited && compare.exit_code == 0) << compare;
  // The localise run's line: line map, confirmed at a scan, then the median / max distance.
  std::istringstream lines(compare.out);
  std::string header, first, second;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_TRUE(testing::Contains(second, "line map")) << compare.out;
  EXPECT_TRUE(testing::Contains(second, "scan ")) << compare.out;
  const std::size_t slash = second.rfind(" / ");
  ASSERT_NE(slash, std::string::npos) << compare.out;
  const double median_m = std::stod(second.substr(second.rfind(' ', slash - 1) + 1));
  const double max_m = std::stod(second.substr(slash + 3));
  EXPECT_LT(median_m, 0.02);
  EXPECT_LT(max_m, 0.05) << "the ambiguous scans are the hypothesis the rules kept best";
}

TEST_F(LocaliseCliTest, OnASessionsPointMapRule2sPriorIsTheMapsOwnSignatureUnlessTurnedOff) {
  const auto session =
      testing::RunScanloc({"session", "--log", Classroom("classroom.seq.jsonl"), "--initial-pose",
                           "1.126", "3.112", "0.0463", "--out", dir_ + "/session", "--quiet"},
                          dir_);
  ASSERT_TRUE(session.exited && session.exit_code == 0) << session;
  const auto written =
      nlohmann::json::parse(testing::ReadWholeFile(dir_ + "/session/summary.json"));
  const auto& signature = written["map_signature"];
  ASSERT_TRUE(signature.is_object()) << written.dump(2);
  EXPECT_TRUE(signature["learned"].get<bool>());
  EXPECT_EQ(signature["scans"].get<int>(), written["validated"].get<int>())
      << "every confirmed scan laid (fewer than the sample holds)";
  const double bound = signature["max_expect_value_m"].get<double>();
  EXPECT_GE(bound, 0.1) << "never below the prior";
  EXPECT_LT(bound, 0.2);
  EXPECT_LT(signature["median_expect_value_m"].get<double>(), bound);
  ASSERT_EQ(signature["samples"].size(), signature["scans"].get<std::size_t>())
      << "one [x, y, EV] per scan it learned from";
  for (const auto& sample : signature["samples"]) {
    ASSERT_EQ(sample.size(), 3u);
    EXPECT_GE(sample[2].get<double>(), 0.0);
  }
  const auto e_max = [&](const std::string& map, const std::string& out,
                         std::vector<std::string> more) {
    std::vector<std::string> words{"localise",      "--log", Classroom("classroom.seq.jsonl"),
                                   "--point-map",   map,     "--out",
                                   dir_ + "/" + out};
    words.insert(words.end(), more.begin(), more.end());
    const auto run = testing::RunScanloc(words, dir_);
    EXPECT_TRUE(run.exited && run.exit_code == 0) << run;
    const auto summary =
        nlohmann::json::parse(testing::ReadWholeFile(dir_ + "/" + out + "/summary.json"));
    return std::make_pair(summary["config"]["validation"]["max_expect_value_m"].get<double>(),
                          run.err);
  };
  const std::string map = dir_ + "/session/map.pcd";
  const auto [used, said] = e_max(map, "signature", {});
  EXPECT_DOUBLE_EQ(used, bound);
  EXPECT_TRUE(testing::Contains(said, "the map's own signature")) << said;
  EXPECT_TRUE(testing::Contains(said, "rule 2's bound raised where the map's")) << said;
  const auto [same, unsaid] = e_max(map, "flat", {"--set", "localise.place_bound=false"});
  EXPECT_DOUBLE_EQ(same, bound);
  EXPECT_FALSE(testing::Contains(unsaid, "bound raised")) << unsaid;
  EXPECT_DOUBLE_EQ(e_max(map, "prior", {"--set", "localise.map_signature=false"}).first, 0.1);
  // A map copied without its summary: the prior, and the run says so.
  std::filesystem::create_directories(dir_ + "/alone");
  std::filesystem::copy_file(map, dir_ + "/alone/map.pcd");
  const auto [alone, told] = e_max(dir_ + "/alone/map.pcd", "alone-run", {});
  EXPECT_DOUBLE_EQ(alone, 0.1);
  EXPECT_TRUE(testing::Contains(told, "no map signature in")) << told;
}

// A classroom session's point map copied to map/map.pcd, its summary left behind.
void LocaliseCliTest::CopySessionMapWithoutItsSummary() {
  std::filesystem::create_directories(dir_ + "/map");
  const auto session =
      testing::RunScanloc({"session", "--log", Classroom("classroom.seq.jsonl"), "--initial-pose",
                           "1.126", "3.112", "0.0463", "--out", dir_ + "/session", "--quiet"},
                          dir_);
  ASSERT_TRUE(session.exited && session.exit_code == 0) << session;
  std::filesystem::copy_file(dir_ + "/session/map.pcd", dir_ + "/map/map.pcd");
}

TEST_F(LocaliseCliTest, AMalformedSummaryBesideTheMapIsNamedAndNothingIsWritten) {
  ASSERT_NO_FATAL_FAILURE(CopySessionMapWithoutItsSummary());
  testing::WriteText(dir_ + "/map/summary.json", "{\"map_signature\": {\"learned\": true}}");
  const auto run =
      testing::RunScanloc({"localise", "--log", Classroom("classroom.seq.jsonl"), "--point-map",
                           dir_ + "/map/map.pcd", "--out", dir_ + "/run", "--quiet"},
                          dir_);
  ASSERT_TRUE(run.exited) << run;
  EXPECT_NE(run.exit_code, 0);
  EXPECT_TRUE(testing::Contains(run.err, "map/summary.json")) << run;
  EXPECT_TRUE(testing::Contains(run.err, "max_expect_value_m")) << run;
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/run")) << "a run folder was created";
}

TEST_F(LocaliseCliTest, AMalformedSampleInTheMapSignatureIsNamedAndNothingIsWritten) {
  ASSERT_NO_FATAL_FAILURE(CopySessionMapWithoutItsSummary());
  for (const std::string samples : {"[[1.0, 2.0, 0.05], [1.0, 2.0]]", "[[1.0, 2.0, -0.05]]"}) {
    testing::WriteText(dir_ + "/map/summary.json",
                       "{\"map_signature\": {\"learned\": true, \"max_expect_value_m\": 0.12, "
                       "\"median_expect_value_m\": 0.07, \"samples\": " +
                           samples + "}}");
    const auto run =
        testing::RunScanloc({"localise", "--log", Classroom("classroom.seq.jsonl"), "--point-map",
                             dir_ + "/map/map.pcd", "--out", dir_ + "/run", "--quiet"},
                            dir_);
    ASSERT_TRUE(run.exited) << run;
    EXPECT_NE(run.exit_code, 0) << samples;
    EXPECT_TRUE(testing::Contains(run.err, "map/summary.json")) << run;
    EXPECT_TRUE(testing::Contains(run.err, "samples")) << run;
    EXPECT_FALSE(std::filesystem::exists(dir_ + "/run")) << "a run folder was created";
  }
}

TEST_F(LocaliseCliTest, WithoutAMapItIsRefusedAndNothingIsWritten) {
  const auto run = testing::RunScanloc(
      {"localise", "--log", Classroom("classroom.seq.jsonl"), "--out", dir_ + "/run", "--quiet"},
      dir_);
  ASSERT_TRUE(run.exited) << run;
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("localise needs a map"), std::string::npos) << run;
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/run")) << "a run folder was created";
}

}  // namespace
}  // namespace scanloc
