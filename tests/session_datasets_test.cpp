// Sessions on prefixes of the public logs, end to end through `scanloc session` and the
// relations metric: a regression guard for the accuracy docs/BENCHMARKS.md reports on the whole
// logs. Skips when the logs are absent (in CI they are present and these run).

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "scanloc/evaluation/relations_evaluation.hpp"
#include "scanloc/io/trajectory.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

class SessionOnPublicLog : public testing::TemporaryDirTest {
 protected:
  // Runs the default session on the first `scans` scans of `log` and scores it on the relations
  // whose both scans it covered.
  // `settings` (KEY=VALUE) go to the session with --set.
  // `log_path` replaces the public log (a copy of it edited by the test).
  RelationsEvaluation RunPrefix(const std::string& log, int scans,
                                const std::vector<std::string>& settings = {},
                                const std::string& log_path = "") {
    const std::string datasets = testing::DatasetsDir();
    const std::string out = dir_ + "/" + log;
    std::vector<std::string> arguments = {
        "session",
        "--log",
        log_path.empty() ? datasets + "/" + log + ".clf.gz" : log_path,
        "--out",
        out,
        "--max-scans",
        std::to_string(scans),
        "--quiet"};
    for (const std::string& setting : settings) {
      arguments.push_back("--set");
      arguments.push_back(setting);
    }
    run_ = testing::RunScanloc(arguments, dir_);
    EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
    // The relations are the scans': the robot's postures are scored through the run's mounting.
    return EvaluateRelations(testing::RunLaserPoses(out),
                             ReadRelations(datasets + "/" + log + ".relations"));
  }

  // LOG.clf.gz as scripts/log-variants.py VARIANT ARGUMENTS... writes it, into OUT under the
  // test's folder; "" when the script failed (the test then fails saying so).
  std::string Variant(const std::string& variant, const std::string& log, const std::string& out,
                      const std::vector<std::string>& arguments) {
    const std::string path = dir_ + "/" + out;
    std::vector<std::string> words = {
        "python3", std::string(SCANLOC_SOURCE_DIR) + "/scripts/log-variants.py", variant,
        testing::DatasetsDir() + "/" + log + ".clf.gz", path};
    words.insert(words.end(), arguments.begin(), arguments.end());
    const auto made = testing::RunCommand(words, dir_);
    EXPECT_TRUE(made.exited && made.exit_code == 0) << made.err;
    return made.exited && made.exit_code == 0 ? path : "";
  }

  // The default session on the first `scans` scans of LOG as a laser seeing only its central
  // 120° would have logged it (scripts/log-variants.py narrow).
  RelationsEvaluation RunSeenOver120Degrees(const std::string& log, int scans) {
    const std::string narrow = Variant("narrow", log, log + "-120.clf", {"120"});
    EXPECT_FALSE(narrow.empty());
    return RunPrefix(log, scans, {}, narrow);
  }

  testing::ScanlocRun run_;  // the last RunPrefix's
};

#define SKIP_WITHOUT_LOGS() \
  if (testing::DatasetsDir().empty()) GTEST_SKIP() << testing::kNoDatasets

// The bounds every prefix asserts: enough relations scored, a mean under `max_mean_m`, no
// relation error of half a metre (the session never diverges) and a mean rotation under 1°.
void ExpectAccurate(const RelationsEvaluation& e, std::size_t min_matched, double max_mean_m) {
  EXPECT_GE(e.matched, min_matched);
  EXPECT_LT(e.translation_m.mean, max_mean_m);
  EXPECT_LT(e.translation_m.max, 0.5);
  EXPECT_LT(e.rotation_deg.mean, 1.0);
}

// Measured 2026-11-22: 541 relations, 0.0161 ± 0.0122 m, max 0.180 m (raw odometry on the whole
// log: 7.37 m).
TEST_F(SessionOnPublicLog, IntelFirst3000ScansStayWithin25MillimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  ExpectAccurate(RunPrefix("intel", 3000), 500, 0.025);
}

// Measured 2026-11-22: 404 relations, 0.0330 ± 0.0266 m, max 0.153 m.
TEST_F(SessionOnPublicLog, AcesFirst2500ScansStayWithin45MillimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  ExpectAccurate(RunPrefix("aces", 2500), 380, 0.045);
}

// ACES under a rotation tolerance moved by 10 % (the robustness harness's perturbation 8), through
// the turn at scans 2,770–2,790 where no scan passes rule 2: the unconfirmed guess once kept there
// a refinement 0.32 rad off the prediction's cheaper one, and the run ended 0.575 m off on average,
// 19 m at worst. Measured 2026-12-05 on the first 3,200 scans: 536 relations, 0.0324 ± 0.0263 m,
// max 0.209 m, rotation max 5.5°; with the old guess put back for the measurement, max 0.549 m
// and 29.4°.
TEST_F(SessionOnPublicLog, AcesUnderAPerturbedToleranceKeepsItsHeadingThroughTheTurnAt2788) {
  SKIP_WITHOUT_LOGS();
  const RelationsEvaluation e =
      RunPrefix("aces", 3200, {"refinement.ceres.rotation_tolerance_rad=0.0011"});
  ExpectAccurate(e, 500, 0.045);
  EXPECT_LT(e.rotation_deg.max, 10.0);
}

// ACES as a short-range laser sees it (readings beyond 5.6 m taken as no return, as
// scripts/variant-sessions.sh's short-range variant does): along the corridor at t = 1070–1095 s
// the scans see no end, and the matcher slid backwards a few centimetres at every scan, each step
// within the correction gate's bound, 4.6 m in all. The slide check (correction_drift.hpp) holds
// the scans at the prediction once the corrections summed over 5 m of path go beyond 8 times
// their learned median. Measured 2026-12-07 on the whole log (1,279 relations): 0.119 m mean, the
// worst relation within 15 s 0.43 m (0.101 m and 0.60 m since a closure's jump is no path driven
// for the check, 73299a8); with the check off (session.correction_drift_window_m=0) 0.319 m and
// 0.65 m.
TEST_F(SessionOnPublicLog, AcesSeenUpTo5Point6MetresDoesNotSlideAlongItsLongCorridor) {
  SKIP_WITHOUT_LOGS();
  const RelationsEvaluation e = RunPrefix("aces", 100000, {"log.no_return_m=5.6"});
  EXPECT_GE(e.matched, 1200u);
  EXPECT_LT(e.translation_m.mean, 0.2);
}

// Intel's first 3,000 scans with every pose field zeroed: the odometry never moves while the
// scans do. The session sets it aside once the ranges moved (after the 144 scans the robot stands
// still), localises every scan without it and warns. Measured 2026-12-06: 2,835 scans localised
// without odometry (28 of them searched for), 541 relations, 0.0147 ± 0.0092 m, max 0.068 m;
// before, one scan was localised, the trajectory stood still at the origin and scored 0.476 m,
// max 1.14 m, without a warning.
TEST_F(SessionOnPublicLog, IntelWithItsPoseFieldsZeroedIsTrackedWithoutTheOdometryAndSaysSo) {
  SKIP_WITHOUT_LOGS();
  const std::string zeroed = dir_ + "/intel-zeroed.clf.gz";
  testing::WriteWithZeroedOdometry("intel", zeroed);
  ExpectAccurate(RunPrefix("intel", 3000, {}, zeroed), 500, 0.025);
  EXPECT_NE(run_.err.find("warning: the log's odometry had not moved"), std::string::npos) << run_;
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir_ + "/intel/summary.json"),
                                                       nullptr, /*allow_exceptions=*/true);
  EXPECT_GT(summary["odometry_frozen_scans"].get<std::size_t>(), 2500u);
  EXPECT_GT(summary["localised_without_odometry"].get<std::size_t>(), 2800u);
}

// Measured 2026-11-27, the laser's poses scored (the relations are the scans'): 573 relations,
// 0.0340 ± 0.0253 m, max 0.194 m; the robot's postures, 0.04 m behind the laser, scored 0.0503 m.
// Fr079's 360-beam scans, long corridors, laser mounting and odometry reversal repair are covered
// by no other guard.
TEST_F(SessionOnPublicLog, Fr079First2000ScansStayWithin45MillimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  ExpectAccurate(RunPrefix("fr079", 2000), 550, 0.045);
}

// Relations between the scans of `run_folder`'s trajectory from the corrected poses of `log`:
// each scan to the next and to the first at least 10 s later (the local relations of the Radish
// logs, for a log kept sparse).
std::vector<Relation> LocalRelations(const std::string& log, const std::string& run_folder) {
  std::map<long long, Pose2D> reference;  // by the timestamp in milliseconds
  for (const StampedPose& p :
       ReadCorrectedPoses(testing::DatasetsDir() + "/" + log + ".corrected-poses.txt"))
    reference[std::llround(p.timestamp_s * 1e3)] = p.pose;
  std::vector<double> times;
  for (const StampedPose& p : testing::RunLaserPoses(run_folder))
    if (reference.count(std::llround(p.timestamp_s * 1e3))) times.push_back(p.timestamp_s);
  std::vector<Relation> relations;
  const auto relate = [&](double a, double b) {
    relations.push_back(
        {a, b, Between(reference[std::llround(a * 1e3)], reference[std::llround(b * 1e3)])});
  };
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    relate(times[i], times[i + 1]);
    const auto later = std::lower_bound(times.begin() + i + 1, times.end(), times[i] + 10.0);
    if (later != times.end()) relate(times[i], *later);
  }
  return relations;
}

// Fr079 kept as a sparse log is: a scan after every 0.8 m or 0.3 rad of odometry (802 of 4,934),
// every ODOM kept. Between two scans the robot may drive forward and then reverse, which the log's
// odometry records as forward. Measured 2026-12-06 on the 1,593 local relations: 0.0464 ± 0.0364
// m, max 0.54 m. When the reversal repair judged a scan's increment by every velocity since the
// scan before, none of those increments was repaired and the session lost its track for 46
// scans: 0.143 ± 0.428 m, max 4.72 m.
TEST_F(SessionOnPublicLog, Fr079KeptAScanAMetreHoldsItsTrackThroughTheReversals) {
  SKIP_WITHOUT_LOGS();
  const std::string sparse = dir_ + "/fr079-sparse.clf.gz";
  testing::WriteSparse("fr079", sparse);
  RunPrefix("fr079", 100000, {}, sparse);
  const std::string out = dir_ + "/fr079";
  const RelationsEvaluation e =
      EvaluateRelations(testing::RunLaserPoses(out), LocalRelations("fr079", out));
  EXPECT_GT(e.matched, 1500u);
  EXPECT_LT(e.translation_m.mean, 0.08);
  EXPECT_LT(e.translation_m.max, 1.0);
}

// ACES as a laser seeing only its central 120° would have logged it (scripts/log-variants.py
// narrow). Past t = 686 s the robot turns on the spot where the narrower scans fit the map worse
// than the laser signature allows, and 150 scans in a row fail rule 2. Their refinements, kept as
// unconfirmed guesses, turned the posture 55° and moved it 6.4 m while the correction gate let
// turns through as an odometry's slip, and the session never found its map again: 0.62 m mean,
// 20.5 m max. Within such a stretch, a refinement the rules rejected is now refused beyond the
// gate's bound whatever its support (correction_gate.hpp, refuse_unvalidated): measured
// 2026-12-07, 0.036 m mean, 0.35 m max (as logged over 180°: 0.035 m, 0.40 m).
TEST_F(SessionOnPublicLog, AcesSeenOver120DegreesKeepsItsMapThroughAStretchTheRulesReject) {
  SKIP_WITHOUT_LOGS();
  ExpectAccurate(RunSeenOver120Degrees("aces", 100000), 1200, 0.05);
}

// Fr079 seen over 120°, its first 1,200 scans. At scan 997 a batch of closures taught the
// odometry model its second lesson, which one closure cannot disprove: the odometry's steps, 2.2
// m and 0.66 rad off the closure over 17.8 m of path (the matched chain 0.1 m), then held the
// graph, which set the batch aside but kept the 2 m bend it had made; the map was rendered from
// it and the session lost its place (0.53 m mean, 6.8 m max). The batch is now solved again
// without that lesson and holds (loop_closure.hpp, set_aside_whole_batch): measured 2026-12-07,
// 0.028 m mean, 0.17 m max.
TEST_F(SessionOnPublicLog, Fr079SeenOver120DegreesHoldsABatchItsOwnOdometryLessonBentAway) {
  SKIP_WITHOUT_LOGS();
  ExpectAccurate(RunSeenOver120Degrees("fr079", 1200), 250, 0.05);
}

}  // namespace
}  // namespace scanloc
