// Map modes compared on a sequence with ground truth: the library's runs and `scanloc compare`.

#include "scanloc/evaluation/mode_comparison.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "environment_fixtures.hpp"
#include "run_scanloc.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

using testing::EnvironmentDir;

const std::string kClassroomSequence = EnvironmentDir("classroom") + "/classroom.seq.jsonl";
const std::string kClassroomMap = EnvironmentDir("classroom") + "/classroom.lines";

TEST(MapMode, NamesParseAndUnknownOnesAreRefused) {
  EXPECT_EQ(ParseMapMode("lines"), MapMode::kLineMap);
  EXPECT_EQ(ParseMapMode("points"), MapMode::kPointMap);
  EXPECT_EQ(ParseMapMode("both"), MapMode::kBoth);
  EXPECT_STREQ(ToString(MapMode::kPointMap), "point map");
  EXPECT_THROW(ParseMapMode("grid"), std::invalid_argument);
}

TEST(RunMode, FixedLineMapTracksTheClassroomWithinMillimetresAndNeverGrowsAMap) {
  const ModeResult r =
      RunMode(MapMode::kLineMap, kClassroomSequence, ReadLineMap(kClassroomMap), Config{}, 20);
  EXPECT_EQ(r.iterations, 20u);
  EXPECT_EQ(r.localised, 20u);  // the first too: the map is there from the start
  EXPECT_EQ(r.validated, 20u);
  EXPECT_EQ(r.with_truth, 20u);
  EXPECT_LT(r.mean_translation_error_m, 0.005);  // measured 0.9 mm over the whole path
  EXPECT_LT(r.max_translation_error_m, 0.01);
  EXPECT_LT(r.max_rotation_error_rad, 0.003);
  EXPECT_EQ(r.map_points, 0u);
  EXPECT_GT(r.mean_match_ratio, 0.7);
  EXPECT_LT(r.mean_expect_value_m, 0.03);
  EXPECT_NEAR(r.mean_match_ratio * r.mean_valid_pairs, r.mean_match_pairs,
              0.02 * r.mean_match_pairs);
  EXPECT_GT(r.mean_iteration_s, 0.0);
}

TEST(RunMode, PointMapStartsAtTheFirstTruthAndGrowsFromNothing) {
  const ModeResult points = RunMode(MapMode::kPointMap, kClassroomSequence, {}, Config{}, 12);
  EXPECT_EQ(points.iterations, 12u);
  EXPECT_EQ(points.with_truth, 11u);  // the first posture is given, not estimated
  EXPECT_LE(points.localised, 11u);
  EXPECT_GT(points.map_points, 100u);
  EXPECT_LT(points.max_translation_error_m, 0.05);
  const ModeResult both =
      RunMode(MapMode::kBoth, kClassroomSequence, ReadLineMap(kClassroomMap), Config{}, 12);
  EXPECT_EQ(both.with_truth, 12u);
  EXPECT_GT(both.map_points, 100u);
}

TEST(RunMode, ModesThatNeedTheLineMapRefuseAnEmptyOne) {
  EXPECT_THROW(RunMode(MapMode::kLineMap, kClassroomSequence, {}, Config{}, 1),
               std::invalid_argument);
  EXPECT_THROW(RunMode(MapMode::kBoth, kClassroomSequence, {}, Config{}, 1), std::invalid_argument);
}

class CompareWithoutTruth : public testing::TemporaryDirTest {};

TEST_F(CompareWithoutTruth, ErrorsAreNotAvailableAndTheTableSaysSo) {
  // The classroom's first iterations written again without their truth.
  const std::string path = dir_ + "/no-truth.seq.jsonl";
  {
    SequenceFileSource source(kClassroomSequence);
    SequenceFileWriter writer(path, source.mounting());
    Iteration iteration;
    for (int i = 0; i < 3 && source.Next(iteration); ++i) writer.Write(iteration);
    writer.Close();
  }
  const ModeResult r = RunMode(MapMode::kLineMap, path, ReadLineMap(kClassroomMap), Config{});
  EXPECT_EQ(r.iterations, 3u);
  EXPECT_EQ(r.with_truth, 0u);
  std::ostringstream table;
  PrintComparison(table, {r});
  EXPECT_NE(table.str().find("n/a"), std::string::npos) << table.str();
}

class CompareCommand : public testing::TemporaryDirTest {
 protected:
  testing::ScanlocRun Run(const std::vector<std::string>& arguments) const {
    return testing::RunScanloc(arguments, dir_);
  }
};

TEST_F(CompareCommand, PrintsOneRowPerModeWithErrorsMomentsAndTime) {
  const auto r = Run({"compare", "--sequence", kClassroomSequence, "--line-map", kClassroomMap,
                      "--max-iterations", "6"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  for (const char* part : {"trans. error mean/max", "MP/NVP", "EV [m]", "ms/iter.", "\nline map ",
                           "\npoint map ", "\nboth ", " mm ", " mrad "})
    EXPECT_NE(r.out.find(part), std::string::npos) << part << "\n" << r;
}

TEST_F(CompareCommand, JsonGivesTheModesAskedForInOrder) {
  const auto r = Run({"compare", "--sequence", kClassroomSequence, "--line-map", kClassroomMap,
                      "--max-iterations", "5", "--modes", "both,lines", "--json"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  std::istringstream lines(r.out);
  std::vector<nlohmann::json> rows;
  for (std::string line; std::getline(lines, line);) rows.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(rows.size(), 2u) << r;
  EXPECT_EQ(rows[0]["mode"], "both");
  EXPECT_EQ(rows[1]["mode"], "line map");
  EXPECT_EQ(rows[1]["iterations"], 5);
  EXPECT_EQ(rows[1]["validated"], 5);
  EXPECT_LT(rows[1]["max_translation_error_m"].get<double>(), 0.01);
  EXPECT_TRUE(rows[1].contains("mean_expect_value_m"));
}

TEST_F(CompareCommand, TheOperatorsLineForTheBlindsIsASecondLineMapFile) {
  const std::string office = EnvironmentDir("office");
  const auto r = Run({"compare", "--sequence", office + "/office.seq.jsonl", "--line-map",
                      office + "/office.lines", office + "/blinds.lines", "--modes", "lines",
                      "--max-iterations", "3"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  EXPECT_NE(r.out.find("line map of 9 segments"), std::string::npos) << r;
}

TEST_F(CompareCommand, BadInputFailsCleanlyWithItsCause) {
  auto r = Run({"compare", "--sequence", kClassroomSequence, "--line-map", kClassroomMap, "--modes",
                "grid"});
  EXPECT_TRUE(r.exited && r.exit_code != 0) << r;
  EXPECT_NE(r.err.find("grid"), std::string::npos) << r;

  r = Run({"compare", "--sequence", kClassroomSequence});
  EXPECT_TRUE(r.exited && r.exit_code != 0) << r;
  EXPECT_NE(r.err.find("--line-map"), std::string::npos) << r;

  const std::string broken =
      Write("broken.seq.jsonl", "{\"scanloc_sequence\": 1}\n{\"scan\": 3}\n");
  r = Run({"compare", "--sequence", broken, "--line-map", kClassroomMap});
  EXPECT_TRUE(r.exited && r.exit_code != 0) << r;
  EXPECT_NE(r.err.find("broken.seq.jsonl:2"), std::string::npos) << r;
  EXPECT_TRUE(r.out.empty()) << r;
}

}  // namespace
}  // namespace scanloc
