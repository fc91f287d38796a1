// End-to-end tests of the `scanloc` executable: exit status, table, JSON, and the messages for bad
// input, which must name file and line and never come from a crash.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "scanloc/io/scan_file.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/io/trajectory.hpp"
#include "scanloc/maps/point_map_io.hpp"
#include "scanloc/worlds/laser_simulator.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

const std::string kClassroom = std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom";
const std::string kMap = kClassroom + "/classroom.lines";
const std::string kScan = kClassroom + "/scan.scan";
const std::string kCandidates = kClassroom + "/candidates.txt";

using RunResult = testing::ScanlocRun;
using testing::ReadWholeFile;

class CliTest : public testing::TemporaryDirTest {
 protected:
  // Runs SCANLOC_BINARY with `arguments` (no shell: nothing to quote), stdout and stderr captured.
  RunResult Run(const std::vector<std::string>& arguments) const {
    const RunResult result = testing::RunScanloc(arguments, dir_);
    if (!result.exited && result.err.rfind("cannot start", 0) == 0)
      ADD_FAILURE() << "cannot start " << SCANLOC_BINARY;
    return result;
  }

  // The classroom job with some inputs or options replaced.
  static std::vector<std::string> TestJob(const std::string& map, const std::string& scan,
                                          const std::string& candidates,
                                          const std::vector<std::string>& extra = {}) {
    std::vector<std::string> arguments = {"test", "--scan", scan, "--candidates", candidates};
    if (!map.empty()) arguments.insert(arguments.end(), {"--map", map});
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    return arguments;
  }

  // The run failed cleanly (exit code ≠ 0, no signal) with `expected` in its message.
  static void ExpectCleanFailure(const RunResult& r, const std::string& expected) {
    EXPECT_TRUE(r.exited) << r;
    EXPECT_NE(r.exit_code, 0) << r;
    EXPECT_NE(r.err.find(expected), std::string::npos) << "expected '" << expected << "'\n" << r;
    EXPECT_TRUE(r.out.empty()) << "no partial result on stdout\n" << r;
  }
};

using testing::Contains;

// The table row of candidate `label`.
std::string RowOf(const std::string& table, const std::string& label) {
  for (std::size_t begin = 0; begin < table.size();) {
    const std::size_t end = table.find('\n', begin);
    const std::string line = table.substr(begin, end - begin);
    if (line.rfind(label + " ", 0) == 0) return line;
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return "";
}

TEST_F(CliTest, ClassroomJobAcceptsP0AsBestAndRejectsP3ByRule3) {
  const RunResult r = Run(TestJob(kMap, kScan, kCandidates));
  ASSERT_TRUE(r.exited) << r;
  ASSERT_EQ(r.exit_code, 0) << r;
  EXPECT_TRUE(Contains(r.out, "best: p0")) << r;
  EXPECT_TRUE(Contains(RowOf(r.out, "p0"), "yes")) << r;
  EXPECT_TRUE(Contains(RowOf(r.out, "p0"), "rank 0")) << r;
  EXPECT_TRUE(Contains(RowOf(r.out, "p3"), "no")) << r;
  EXPECT_TRUE(Contains(RowOf(r.out, "p3"), "rule 3")) << r;
  EXPECT_FALSE(Contains(r.out, "problem:")) << r;
}

TEST_F(CliTest, JsonOutputHasFourCandidatesWithTwentySlotHistograms) {
  const RunResult r = Run(TestJob(kMap, kScan, kCandidates, {"--json"}));
  ASSERT_TRUE(r.exited) << r;
  ASSERT_EQ(r.exit_code, 0) << r;
  nlohmann::json out;
  ASSERT_NO_THROW(out = nlohmann::json::parse(r.out)) << r;
  EXPECT_EQ(out.at("best"), "p0");
  const auto& candidates = out.at("candidates");
  ASSERT_EQ(candidates.size(), 4u);
  const char* labels[] = {"p0", "p1", "p2", "p3"};
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& c = candidates[i];
    EXPECT_EQ(c.at("label"), labels[i]);
    const auto& test = c.at("likelihood_test");
    const auto& histogram = test.at("histogram");
    ASSERT_EQ(histogram.size(), 20u) << labels[i];
    // (3.8) MatchPairs is the histogram's sum.
    int sum = 0;
    for (const auto& t : histogram) sum += t.get<int>();
    EXPECT_EQ(sum, test.at("match_pairs").get<int>()) << labels[i];
    EXPECT_LE(test.at("match_pairs").get<int>(), test.at("valid_pairs").get<int>()) << labels[i];
  }
  EXPECT_TRUE(candidates[0].at("valid").get<bool>());
  EXPECT_EQ(candidates[0].at("rank"), 0);
  EXPECT_FALSE(candidates[3].at("valid").get<bool>());
  EXPECT_TRUE(Contains(candidates[3].at("reason").get<std::string>(), "rule 3"));
  EXPECT_EQ(out.at("config").at("likelihood_test").at("slot_count"), 20);
}

TEST_F(CliTest, SetSlotCountChangesTheHistogramLength) {
  const RunResult r =
      Run(TestJob(kMap, kScan, kCandidates, {"--json", "--set", "likelihood_test.slot_count=30"}));
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  const auto out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out.at("candidates")[0].at("likelihood_test").at("histogram").size(), 30u);
}

// `scanloc refine` builds its refiner from the configuration: --set reaches the Ceres options.
// The refined postures are compared (the table's time column differs from run to run anyway).
TEST_F(CliTest, RefineHonoursSetRefinementOptions) {
  std::vector<std::string> refine = {"refine", "--map",        kMap,        "--scan",
                                     kScan,    "--candidates", kCandidates, "--json"};
  const RunResult defaults = Run(refine);
  ASSERT_TRUE(defaults.exited && defaults.exit_code == 0) << defaults;
  refine.insert(refine.end(), {"--set", "refinement.ceres.max_outer_iterations=1"});
  const RunResult one_step = Run(refine);
  ASSERT_TRUE(one_step.exited && one_step.exit_code == 0) << one_step;
  const auto before = nlohmann::json::parse(defaults.out),
             after = nlohmann::json::parse(one_step.out);
  EXPECT_EQ(after.at("config").at("refinement").at("ceres").at("max_outer_iterations"), 1);
  ASSERT_EQ(before.at("candidates").size(), after.at("candidates").size());
  int changed = 0;
  for (std::size_t i = 0; i < before.at("candidates").size(); ++i) {
    const auto& b = before.at("candidates")[i];
    const auto& a = after.at("candidates")[i];
    EXPECT_EQ(a.at("refinement").at("iterations"), 1) << i;
    changed += a.at("refined_T_world_robot") != b.at("refined_T_world_robot");
  }
  EXPECT_GT(changed, 0) << "the refined postures are the defaults'";
}

// The method comes from --config unless --method names one.
TEST_F(CliTest, RefineTakesItsMethodFromTheConfigFile) {
  const std::string config =
      Write("descent.json", R"({"refinement": {"method": "error-descent"}})");
  const std::vector<std::string> refine = {"refine",       "--map",     kMap,       "--scan", kScan,
                                           "--candidates", kCandidates, "--config", config};
  const RunResult from_file = Run(refine);
  ASSERT_TRUE(from_file.exited && from_file.exit_code == 0) << from_file;
  EXPECT_TRUE(Contains(from_file.out, "method: error-descent")) << from_file;
  std::vector<std::string> overridden = refine;
  overridden.insert(overridden.end(), {"--method", "ceres"});
  const RunResult from_flag = Run(overridden);
  ASSERT_TRUE(from_flag.exited && from_flag.exit_code == 0) << from_flag;
  EXPECT_TRUE(Contains(from_flag.out, "method: ceres")) << from_flag;
}

TEST_F(CliTest, TinyExpectValueLimitRejectsEveryCandidateByRule2) {
  const RunResult r =
      Run(TestJob(kMap, kScan, kCandidates, {"--set", "validation.max_expect_value_m=0.001"}));
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  for (const char* label : {"p0", "p1", "p2", "p3"}) {
    const std::string row = RowOf(r.out, label);
    EXPECT_TRUE(Contains(row, "rule 2")) << label << ": " << row;
  }
  EXPECT_FALSE(Contains(r.out, "best: p")) << r;
}

TEST_F(CliTest, SetOfTheMovedSessionExpectValueNamesItsNewKey) {
  ExpectCleanFailure(
      Run(TestJob(kMap, kScan, kCandidates, {"--set", "session.max_expect_value_m=0.1"})),
      "validation.max_expect_value_m");
}

TEST_F(CliTest, SetOfANumberBeyondADoubleIsRefusedNamingTheKey) {
  ExpectCleanFailure(
      Run(TestJob(kMap, kScan, kCandidates, {"--set", "likelihood_test.slot_width_m=1e400"})),
      "likelihood_test.slot_width_m");
}

TEST_F(CliTest, SessionRefusesAnAbsurdInitialHeadingNamingTheOption) {
  ExpectCleanFailure(Run({"session", "--log", kClassroom + "/classroom.seq.jsonl", "--out",
                          dir_ + "/run", "--quiet", "--initial-pose", "0", "0", "1e20"}),
                     "--initial-pose: expected a finite number");
}

TEST_F(CliTest, OptionsCommandListsEveryKey) {
  const RunResult r = Run({"options"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  for (const char* key : {"likelihood_test.slot_count = 20", "validation.alpha_m = 0.1",
                          "refinement.icp.point_to_plane = false", "log.repair_reversed_odometry",
                          "session.initial_pose = [0.0,0.0,0.0]"})
    EXPECT_TRUE(Contains(r.out, key)) << key << "\n" << r;
}

TEST_F(CliTest, LineMapWithABadLineFailsNamingFileAndLine) {
  const std::string map = Write("bad.lines", "0 0 1 0\n# comment\n0 0 x 1\n");
  ExpectCleanFailure(Run(TestJob(map, kScan, kCandidates)), map + ":3:");
}

TEST_F(CliTest, CandidatesFileWithTwoFieldsFailsNamingFileAndLine) {
  const std::string candidates = Write("two.txt", "1.0 2.0 0.0 p0\n1.0 2.0\n");
  ExpectCleanFailure(Run(TestJob(kMap, kScan, candidates)), candidates + ":2:");
}

TEST_F(CliTest, ScanWithNaNInTheHeaderFailsNamingFileAndLine) {
  const std::string scan = Write("nan.scan",
                                 "scanloc_scan 1\nbeams 3\nangle_min_rad nan\n"
                                 "angle_increment_rad 0.5\nranges 1 2 3\n");
  const RunResult r = Run(TestJob(kMap, scan, kCandidates));
  ExpectCleanFailure(r, scan + ":3:");
  EXPECT_TRUE(Contains(r.err, "finite")) << r;
}

TEST_F(CliTest, MissingScanFileFailsNamingIt) {
  const std::string scan = dir_ + "/missing.scan";
  ExpectCleanFailure(Run(TestJob(kMap, scan, kCandidates)), scan);
}

TEST_F(CliTest, SlotCountZeroIsRefused) {
  ExpectCleanFailure(
      Run(TestJob(kMap, kScan, kCandidates, {"--set", "likelihood_test.slot_count=0"})),
      "slot_count");
}

TEST_F(CliTest, UnknownSetKeyIsRefusedWithItsPath) {
  const RunResult r = Run(TestJob(kMap, kScan, kCandidates, {"--set", "validation.nonsense=1"}));
  ExpectCleanFailure(r, "config.validation");
  EXPECT_TRUE(Contains(r.err, "'nonsense'")) << r;
}

TEST_F(CliTest, SetWithoutValueIsRefused) {
  ExpectCleanFailure(
      Run(TestJob(kMap, kScan, kCandidates, {"--set", "likelihood_test.slot_count"})),
      "section.key=value");
}

TEST_F(CliTest, MinMatchRatioAboveOneIsRefused) {
  ExpectCleanFailure(Run(TestJob(kMap, kScan, kCandidates, {"--min-match-ratio", "5"})),
                     "min_match_ratio");
}

// A negative or NaN --min-match-ratio or --match-threshold is refused, not taken for "not given".
TEST_F(CliTest, NegativeMinMatchRatioOrMatchThresholdIsRefused) {
  for (const auto& extra : std::vector<std::vector<std::string>>{{"--min-match-ratio", "-0.5"},
                                                                 {"--min-match-ratio", "nan"},
                                                                 {"--match-threshold", "-3"}}) {
    const RunResult r = Run(TestJob(kMap, kScan, kCandidates, extra));
    EXPECT_TRUE(r.exited) << r;
    EXPECT_NE(r.exit_code, 0) << extra[0] << " " << extra[1] << "\n" << r;
  }
}

TEST_F(CliTest, NoMapIsRefused) {
  ExpectCleanFailure(Run(TestJob("", kScan, kCandidates)), "a map is required");
}

TEST_F(CliTest, EmptyLineMapRunsAndReportsTheProblem) {
  const std::string map = Write("empty.lines", "# nothing here\n");
  const RunResult r = Run(TestJob(map, kScan, kCandidates));
  ASSERT_TRUE(r.exited) << r;
  EXPECT_EQ(r.exit_code, 0) << r;
  EXPECT_TRUE(Contains(r.out, "problem: the map is empty")) << r;
  EXPECT_FALSE(Contains(r.out, "best:")) << r;
}

TEST_F(CliTest, ScanWithoutValidRangeRunsAndReportsTheProblem) {
  std::string ranges;
  for (int i = 0; i < 360; ++i) ranges += "-1\n";
  const std::string scan = Write("dark.scan",
                                 "scanloc_scan 1\nbeams 360\nangle_min_rad -3.14159265358979\n"
                                 "angle_increment_rad 0.0174532925199433\nranges\n" +
                                     ranges);
  const RunResult r = Run(TestJob(kMap, scan, kCandidates));
  ASSERT_TRUE(r.exited) << r;
  EXPECT_EQ(r.exit_code, 0) << r;
  EXPECT_TRUE(Contains(r.out, "problem: the scan has no valid range")) << r;
  EXPECT_FALSE(Contains(r.out, "best:")) << r;
}

TEST_F(CliTest, EmptyMapJsonStillParses) {
  const std::string map = Write("empty.lines", "");
  const RunResult r = Run(TestJob(map, kScan, kCandidates, {"--json"}));
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  nlohmann::json out;
  ASSERT_NO_THROW(out = nlohmann::json::parse(r.out)) << r;
  EXPECT_TRUE(out.at("best").is_null());
  EXPECT_EQ(out.at("problems")[0], "the map is empty");
}

TEST_F(CliTest, SimulateScanWritesTheRequestedBeamCount) {
  const std::string out = dir_ + "/simulated.scan";
  const RunResult r = Run({"simulate-scan", "--world", kMap, "--pose", "1.126", "3.112", "0.0463",
                           "--beams", "720", "--seed", "7", "--out", out});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  const LaserScan scan = ReadScanFile(out);
  EXPECT_EQ(scan.size(), 720u);
  EXPECT_EQ(scan.layout.beam_count, 720u);
  // Inside a closed room every beam hits a wall well within 20 m.
  EXPECT_EQ(scan.CountValid(), 720u);
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir_))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"simulated.scan", "stderr.txt", "stdout.txt"}))
      << "no temporary file remains";
}

TEST_F(CliTest, SimulateScanWithTheSameSeedIsByteIdentical) {
  auto simulate = [&](const std::string& name, const std::string& seed) {
    const std::string out = dir_ + "/" + name;
    const RunResult r =
        Run({"simulate-scan", "--world", kMap, "--pose", "3", "3.5", "0.5", "--beams", "500",
             "--noise", "0.05", "--dropout", "0.1", "--seed", seed, "--out", out});
    EXPECT_TRUE(r.exited && r.exit_code == 0) << r;
    return ReadWholeFile(out);
  };
  const std::string first = simulate("a.scan", "42");
  EXPECT_FALSE(first.empty());
  EXPECT_EQ(simulate("b.scan", "42"), first);
  EXPECT_NE(simulate("c.scan", "43"), first) << "another seed draws other noise";
}

TEST_F(CliTest, ShippedClassroomScanRegeneratesByteForByte) {
  // The command in datasets/README.md: the shipped scan must be what the code makes today.
  const std::string out = dir_ + "/scan.scan";
  const RunResult r = Run({"simulate-scan", "--world", kMap,
                           std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/clutter.lines",
                           "--pose", "1.126", "3.112", "0.0463", "--seed", "7", "--body-sector",
                           "2.7", "3.1416", "--dropout", "0.02", "--out", out});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  EXPECT_EQ(ReadWholeFile(out), ReadWholeFile(kScan));
}

TEST_F(CliTest, SimulateScanIntoMissingDirectoryFailsCleanly) {
  ExpectCleanFailure(Run({"simulate-scan", "--world", kMap, "--pose", "1", "1", "0", "--out",
                          dir_ + "/no/such/dir/x.scan"}),
                     "no/such/dir");
}

TEST_F(CliTest, SimulateScanWithOneBeamIsRefused) {
  ExpectCleanFailure(Run({"simulate-scan", "--world", kMap, "--pose", "1", "1", "0", "--beams", "1",
                          "--out", dir_ + "/x.scan"}),
                     "beam_count");
}

// "--body-sector abc 1" is refused with a message naming the option.
TEST_F(CliTest, SimulateScanBodySectorNotANumberNamesTheOption) {
  ExpectCleanFailure(Run({"simulate-scan", "--world", kMap, "--pose", "1", "1", "0",
                          "--body-sector", "abc", "1", "--out", dir_ + "/x.scan"}),
                     "--body-sector");
}

// "--pose nan 0 0" is refused rather than writing a scan with no valid range.
TEST_F(CliTest, SimulateScanRefusesANonFinitePose) {
  const std::string out = dir_ + "/x.scan";
  const RunResult r =
      Run({"simulate-scan", "--world", kMap, "--pose", "nan", "0", "0", "--out", out});
  ExpectCleanFailure(r, "pose");
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A straight walk through the classroom: 30 scans 5 cm apart, exact odometry, written as a native
// sequence with the truth; and the relations between consecutive true postures.
struct WalkFiles {
  std::string sequence, relations;
};
WalkFiles WriteClassroomWalk(const std::string& dir) {
  const LineMap world = ReadLineMap(kMap);
  LaserSimulatorOptions laser;
  laser.beam_count = 720;
  std::mt19937 rng(11);
  WalkFiles files{dir + "/walk.seq.jsonl", dir + "/walk.relations"};
  SequenceFileWriter writer(files.sequence, LaserMounting{});
  std::ofstream relations(files.relations);
  Pose2D previous;
  for (int i = 0; i < 30; ++i) {
    const Pose2D truth{1.5 + 0.05 * i, 3.0, 0.1};
    Iteration it;
    it.timestamp_s = 100.0 + 0.5 * i;
    it.scan = SimulateLaser(world, truth, laser, rng);
    it.odometry = Pose2D{0.05 * i, 0.0, 0.0};
    writer.Write(it, truth);
    if (i > 0) {
      const Pose2D r = Between(previous, truth);
      relations << it.timestamp_s - 0.5 << ' ' << it.timestamp_s << ' ' << r.x_m << ' ' << r.y_m
                << " 0 0 0 " << r.yaw_rad << '\n';
    }
    previous = truth;
  }
  writer.Close();
  return files;
}

TEST_F(CliTest, SessionOnANativeSequenceWritesCompleteOutputsThatEvaluate) {
  const WalkFiles walk = WriteClassroomWalk(dir_);
  const std::string run = dir_ + "/run";
  const RunResult r = Run({"session", "--log", walk.sequence, "--out", run, "--initial-pose", "1.5",
                           "3.0", "0.1", "--quiet"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  // One JSON record per iteration, the localised ones with their candidates and moments.
  std::ifstream records(run + "/iterations.jsonl");
  int lines = 0, localised = 0;
  for (std::string line; std::getline(records, line); ++lines) {
    const auto record = nlohmann::json::parse(line);
    if (!record["skipped"].get<bool>() && !record["first"].get<bool>()) {
      ++localised;
      EXPECT_EQ(record["candidates"].at(0)["likelihood_test"]["histogram"].size(), 20u);
    }
  }
  EXPECT_EQ(lines, 30);
  // Steps of 5 cm against a threshold of "more than 5 cm": at least every other scan is localised.
  EXPECT_GE(localised, 14);
  const auto summary = nlohmann::json::parse(ReadWholeFile(run + "/summary.json"));
  EXPECT_EQ(summary["iterations"], 30);
  EXPECT_FALSE(summary["interrupted"].get<bool>());
  // The session's CPU time, every thread's (a process cannot burn much more than its wall time
  // times the cores: 2 on the test machines, 64 allowed), and the span over it.
  const double cpu_s = summary["cpu_time_s"].get<double>();
  EXPECT_GE(cpu_s, 0.0);
  EXPECT_LT(cpu_s, 64.0 * summary["wall_time_s"].get<double>() + 0.05);
  if (cpu_s > 0.0) {  // a few milliseconds here: the kernel's accounting may round them away
    EXPECT_NEAR(summary["times_real_time_on_cpu"].get<double>() * cpu_s,
                summary["data_span_s"].get<double>(), 1e-6 * summary["data_span_s"].get<double>());
  }
  EXPECT_GT(LoadPointMapPcd(run + "/map.pcd").size(), 100u);
  EXPECT_EQ(ReadTumTrajectory(run + "/trajectory.tum").size(), 30u);

  const RunResult e = Run({"evaluate", "--trajectory", run + "/trajectory.tum", "--relations",
                           walk.relations, "--json"});
  ASSERT_TRUE(e.exited && e.exit_code == 0) << e;
  const auto metric = nlohmann::json::parse(e.out);
  EXPECT_EQ(metric["matched"], 29);
  EXPECT_LT(metric["translation_m"]["mean"].get<double>(), 0.01);
}

TEST_F(CliTest, SessionRefusesAMalformedSequenceLineNamingFileAndLine) {
  const std::string sequence = Write("bad.seq.jsonl",
                                     "{\"scanloc_sequence\": 1}\n"
                                     "{\"scan\": {\"angle_min_rad\": 0, \"angle_increment_rad\": "
                                     "0.1, \"ranges\": [1, 2, \"x\"]}}\n");
  const RunResult r = Run({"session", "--log", sequence, "--out", dir_ + "/run", "--quiet"});
  EXPECT_TRUE(r.exited) << r;
  EXPECT_NE(r.exit_code, 0) << r;
  EXPECT_NE(r.err.find("bad.seq.jsonl:2:"), std::string::npos) << r;
}

}  // namespace
}  // namespace scanloc

namespace scanloc {
namespace {

class SessionFailureTest : public testing::TemporaryDirTest {};

// A sequence whose sixth line is broken: the session stops there with an error naming the file and
// line, exits ≠ 0, and still writes the trajectory, map and summary of the five scans before it.
TEST_F(SessionFailureTest, AMalformedLineMidRunFailsButKeepsWhatWasDone) {
  std::ifstream in(kClassroom + "/classroom.seq.jsonl");
  std::string text, line;
  for (int i = 0; i < 6 && std::getline(in, line); ++i) text += line + "\n";  // header + 5 scans
  const std::string log = Write("broken.seq.jsonl", text + "{\"timestamp_s\": oops}\n");
  const std::string out = dir_ + "/run";
  const testing::ScanlocRun r =
      testing::RunScanloc({"session", "--log", log, "--line-map", kMap, "--initial-pose", "1.126",
                           "3.112", "0.0463", "--out", out, "--quiet"},
                          dir_);
  ASSERT_TRUE(r.exited) << r;
  EXPECT_NE(r.exit_code, 0) << r;
  EXPECT_NE(r.err.find("broken.seq.jsonl:7"), std::string::npos) << r;
  const nlohmann::json summary =
      nlohmann::json::parse(testing::ReadWholeFile(out + "/summary.json"));
  EXPECT_EQ(summary["iterations"], 5);
  ASSERT_TRUE(summary.contains("failed"));
  EXPECT_NE(summary["failed"].get<std::string>().find("broken.seq.jsonl:7"), std::string::npos);
  EXPECT_EQ(ReadTumTrajectory(out + "/trajectory.tum").size(), 5u);
  EXPECT_GT(LoadPointMapPcd(out + "/map.pcd").live_size(), 0u);
  // The occupancy grid of those five scans is written too.
  EXPECT_EQ(summary["files"]["occupancy_grid"], "map.yaml");
  EXPECT_TRUE(testing::Contains(testing::ReadWholeFile(out + "/map.yaml"), "image: map.pgm"));
  EXPECT_GT(std::filesystem::file_size(out + "/map.pgm"), 100u * 100u);  // a 7 m room at 5 cm
}

// The classroom's first `scans` scans from the operator's posture into `out`, with `extra` words.
testing::ScanlocRun ClassroomSession(const std::string& dir, const std::string& out, int scans,
                                     const std::vector<std::string>& extra = {}) {
  std::vector<std::string> words = {"session",
                                    "--log",
                                    kClassroom + "/classroom.seq.jsonl",
                                    "--line-map",
                                    kMap,
                                    "--initial-pose",
                                    "1.126",
                                    "3.112",
                                    "0.0463",
                                    "--max-scans",
                                    std::to_string(scans),
                                    "--out",
                                    out,
                                    "--quiet"};
  words.insert(words.end(), extra.begin(), extra.end());
  return testing::RunScanloc(words, dir);
}

TEST_F(SessionFailureTest, ANonEmptyOutFolderIsRefusedUntouchedUnlessForced) {
  const std::string out = dir_ + "/run";
  ASSERT_EQ(ClassroomSession(dir_, out, 3).exit_code, 0);
  const std::string trajectory = testing::ReadWholeFile(out + "/trajectory.tum");
  const auto written = std::filesystem::last_write_time(out + "/iterations.jsonl");
  const testing::ScanlocRun again = ClassroomSession(dir_, out, 5);
  ASSERT_TRUE(again.exited) << again;
  EXPECT_NE(again.exit_code, 0) << again;
  EXPECT_TRUE(testing::Contains(again.err, out + " already exists and is not empty")) << again;
  EXPECT_TRUE(testing::Contains(again.err, "--force")) << again;
  EXPECT_EQ(testing::ReadWholeFile(out + "/trajectory.tum"), trajectory);  // nothing touched
  EXPECT_EQ(std::filesystem::last_write_time(out + "/iterations.jsonl"), written);
  const testing::ScanlocRun forced = ClassroomSession(dir_, out, 5, {"--force"});
  EXPECT_EQ(forced.exit_code, 0) << forced;
  EXPECT_EQ(ReadTumTrajectory(out + "/trajectory.tum").size(), 5u);
}

TEST_F(SessionFailureTest, SimulateRefusesANonEmptyOutFolderUnlessForced) {
  Write("kept.txt", "earlier");
  const auto r = testing::RunScanloc(
      {"simulate", "--environment", "classroom", "--iterations", "2", "--out", dir_}, dir_);
  EXPECT_NE(r.exit_code, 0) << r;
  EXPECT_TRUE(testing::Contains(r.err, "already exists and is not empty")) << r;
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/classroom.lines"));
  const auto forced = testing::RunScanloc(
      {"simulate", "--environment", "classroom", "--iterations", "2", "--out", dir_, "--force"},
      dir_);
  EXPECT_EQ(forced.exit_code, 0) << forced;
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/kept.txt"));
}

TEST_F(SessionFailureTest, TheGridOptionsSetItsResolutionOrTurnItOff) {
  const auto coarse =
      ClassroomSession(dir_, dir_ + "/coarse", 3, {"--set", "occupancy_grid.resolution_m=0.1"});
  ASSERT_EQ(coarse.exit_code, 0) << coarse;
  EXPECT_TRUE(
      testing::Contains(testing::ReadWholeFile(dir_ + "/coarse/map.yaml"), "\nresolution: 0.1\n"));
  const auto off =
      ClassroomSession(dir_, dir_ + "/off", 3, {"--set", "occupancy_grid.write=false"});
  ASSERT_EQ(off.exit_code, 0) << off;
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/off/map.pcd"));
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/off/map.pgm"));
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/off/map.yaml"));
  const auto absurd =
      ClassroomSession(dir_, dir_ + "/absurd", 3, {"--set", "occupancy_grid.resolution_m=0"});
  EXPECT_NE(absurd.exit_code, 0) << absurd;
  EXPECT_TRUE(testing::Contains(absurd.err, "occupancy_grid.resolution_m")) << absurd;
}

}  // namespace
}  // namespace scanloc
