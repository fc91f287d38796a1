// The five sparse Radish logs of other buildings (../shared/datasets/radish, see its README):
// a regression guard for the default session on logs it was not tuned on. Where the default
// session holds, its accuracy is asserted; a run that mostly does not must say so loudly. Skips
// when the logs are absent (in CI they are present).

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "scanloc/evaluation/relations_evaluation.hpp"
#include "scanloc/io/trajectory.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

class SessionOnRadishLog : public testing::TemporaryDirTest {
 protected:
  // The default session on radish/NAME.KIND.clf.gz, scored on NAME.RELATIONS.
  RelationsEvaluation Run(const std::string& name, const std::string& kind,
                          const std::string& relations = "relations",
                          std::vector<std::string> extra = {}) {
    const std::string radish = testing::DatasetsDir() + "/radish/";
    return RunOn(radish + name + "." + kind + ".clf.gz", name + "-" + kind,
                 radish + name + "." + relations, std::move(extra));
  }
  // The default session on the log at `log`, written to OUT_NAME, scored on `relations`.
  RelationsEvaluation RunOn(const std::string& log, const std::string& out_name,
                            const std::string& relations, std::vector<std::string> extra = {}) {
    out_ = dir_ + "/" + out_name;
    std::vector<std::string> args = {"session", "--log", log, "--out", out_, "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    run_ = testing::RunScanloc(args, dir_);
    return EvaluateRelations(testing::RunLaserPoses(out_), ReadRelations(relations));
  }
  // radish/NAME.KIND.clf.gz as scripts/log-variants.py VARIANT ARGUMENTS... writes it, into OUT
  // under the test's folder; "" when the script failed (the test then fails saying so).
  std::string Variant(const std::string& variant, const std::string& name, const std::string& kind,
                      const std::string& out, const std::vector<std::string>& arguments) {
    const std::string log = dir_ + "/" + out;
    std::vector<std::string> words = {
        "python3", std::string(SCANLOC_SOURCE_DIR) + "/scripts/log-variants.py", variant,
        testing::DatasetsDir() + "/radish/" + name + "." + kind + ".clf.gz", log};
    words.insert(words.end(), arguments.begin(), arguments.end());
    const auto made = testing::RunCommand(words, dir_);
    EXPECT_TRUE(made.exited && made.exit_code == 0) << made.err;
    return made.exited && made.exit_code == 0 ? log : "";
  }
  nlohmann::json Summary() const {
    std::ifstream in(out_ + "/summary.json");
    return nlohmann::json::parse(in);
  }
  std::string out_;
  testing::ScanlocRun run_;
};

#define SKIP_WITHOUT_LOGS() \
  if (testing::DatasetsDir().empty()) GTEST_SKIP() << testing::kNoDatasets

// Measured 2026-11-23 (defaults): 0.147 m mean, 2.0 m max; local (≤ 15 s) max 0.16 m.
TEST_F(SessionOnRadishLog, SeattleWithNoisyOdometryHoldsLocallyWithin30Centimetres) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("seattle", "noisy").translation_m.mean, 0.2);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
  EXPECT_LT(Run("seattle", "noisy", "local.relations").translation_m.max, 0.3);
}

// Measured 2026-11-25: 0.305 m mean (0.27–0.35 under perturbations of the defaults) with the
// log's 32.76 m no-return code recognised (1.909 m when its readings were phantom walls).
TEST_F(SessionOnRadishLog, OrebroWithItsOwnNoReturnCodeStaysWithin40CentimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("orebro", "noisy").translation_m.mean, 0.4);
  EXPECT_NEAR(Summary()["no_return_m"].get<double>(), 32.76, 0.01);
}

// Issue 15's local target on orebro: scan 213 refined onto the map its newest nodes had laid about
// 0.1 m off, turned 0.108 rad from a prediction right to 0.005 rad, and was confirmed (local max
// 1.01 m, in all ten harness runs). The closure tried at that scan, on older nodes, held the
// prediction's heading and disputed the turn, which is withdrawn (turn_dispute.hpp); measured
// 2026-12-06: local max 0.343 m, 0.171 m mean (0.301 m before); all ten harness runs under 0.5 m.
TEST_F(SessionOnRadishLog, OrebroWithNoisyOdometryHoldsLocallyUnderHalfAMetreOnceATurnIsDisputed) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("orebro", "noisy", "local.relations").translation_m.max, 0.5);
  EXPECT_GE(Summary()["turns_disputed_by_closures"].get<int>(), 1);
}

// Orebro with noisy odometry as a laser 1 cm noisier would have logged it (the noise harness's
// seed 2, scripts/noise-sessions.sh): eight scans into the session, before the slide check has
// learned its bound, scan 11's refinement stopped at its iteration cap 0.35 m along its weakest
// axis and was confirmed, and laid the map there (local max 0.53 m, 0.320 m mean). Now a slide
// still under way is refused before the check learns (correction_gate.hpp, Slides): measured
// 2026-12-07, local max 0.40 m, 0.293 m mean.
TEST_F(SessionOnRadishLog, OrebroWithANoisierLaserHoldsLocallyOnceAnEarlySlideIsRefused) {
  SKIP_WITHOUT_LOGS();
  const std::string log = Variant("range-noise", "orebro", "noisy", "orebro-n2.clf", {"0.01", "2"});
  ASSERT_FALSE(log.empty());
  const std::string relations = testing::DatasetsDir() + "/radish/orebro.local.relations";
  EXPECT_LT(RunOn(log, "orebro-n2", relations).translation_m.max, 0.5);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
  EXPECT_GE(Summary()["slide_refusals"].get<int>(), 1);
}

// Acapulco with noisy odometry, its laser seeing only the central 120° (scripts/log-variants.py
// narrow): rule 2's E_max, learned on the first eight scans, rejects the cluttered hall's good
// fits, the robot drives out of its map, and without mapping on new ground the session confirmed
// 34 of 861 scans and ended 12.93 m off on average (117 m max). Measured 2026-12-07 with it: 817
// confirmed, 0.88 m mean.
TEST_F(SessionOnRadishLog, AcapulcoSeenOver120DegreesMapsOnAlongTheOdometryWhereItHasNoMap) {
  SKIP_WITHOUT_LOGS();
  const std::string log = Variant("narrow", "acapulco", "noisy", "acapulco-120.clf", {"120"});
  ASSERT_FALSE(log.empty());
  const std::string relations = testing::DatasetsDir() + "/radish/acapulco.relations";
  EXPECT_LT(RunOn(log, "acapulco-120", relations).translation_m.mean, 2.0);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
  EXPECT_GT(Summary()["validated"].get<int>(), 700);
  EXPECT_GE(Summary()["new_ground_insertions"].get<int>(), 1);
}

// The log has PARAM lines of five and six fields. Measured 2026-11-25 without loop closure:
// 0.333 m mean (0.331–0.334 under perturbations); 2026-11-29 with loop closure on by default:
// 0.458 m (0.458–0.526), the session lost once it tracks only its newest 10 m of nodes
// (docs/BENCHMARKS.md, "Loop closure on by default"); with the correction gate (2026-11-29,
// night): 0.249 m (0.240–0.252).
TEST_F(SessionOnRadishLog, FhwWithBothParamFormsStaysWithin55CentimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("fhw", "noisy").translation_m.mean, 0.55);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
}

// Issue 15's local target: no relation between scans at most 15 s apart reaches 0.5 m. Before the
// correction gate fhw's track slid 0.5 m along a corridor at scan 203 and was lost after scan 56
// (local max 2.30 m); measured 2026-11-29 with the gate: 0.461 m (under 0.5 m in 9 of the 10
// harness runs, 0.52 m in the tenth).
TEST_F(SessionOnRadishLog, FhwWithNoisyOdometryHoldsLocallyUnderHalfAMetre) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("fhw", "noisy", "local.relations").translation_m.max, 0.5);
}

// Issue 15's local target on acapulco: before the prediction was refined when the rules rejected
// it as given, scans where only a turned candidate passed refined to a heading 0.1 rad off and
// were confirmed (local max 0.590 m, at or above 0.5 m in 9 of the 10 harness runs); measured
// 2026-12-01 with it: 0.396 m (at or above 0.5 m in 1 of 10).
//
// At scan 296 the rules kept a refinement 4.3° off that matched 37 % of the pairs (EV 0.098 m)
// over the prediction's, 1° off at 75 % (EV 0.149 m): every relation across it was up to 4.4 m
// off (0.200 m mean). The session keeps a valid refinement matching more pairs at a lower
// truncated mean (tighter_refinement.hpp; measured 2026-12-07): 0.188 m mean, 2.04 m max (local
// 0.44 m), three such scans kept.
TEST_F(SessionOnRadishLog,
       AcapulcoWithNoisyOdometryHoldsLocallyUnderHalfAMetreAndKeepsTighterRefinements) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("acapulco", "noisy", "local.relations").translation_m.max, 0.5);
  const std::string radish = testing::DatasetsDir() + "/radish/";
  EXPECT_LT(
      EvaluateRelations(testing::RunLaserPoses(out_), ReadRelations(radish + "acapulco.relations"))
          .translation_m.max,
      3.0);
  EXPECT_GE(Summary()["tighter_refinements_kept"].get<int>(), 1);
}

// Edmonton with noisy odometry: unconfirmed scans whose refinement matched less of the scan than
// usual kept it (local max 0.398 m); keeping the prediction there instead (measured 2026-12-01):
// 0.252 m (0.17–0.25 m over the 10 harness runs). The guard lies between the two.
TEST_F(SessionOnRadishLog, EdmontonWithNoisyOdometryHoldsLocallyWithin35Centimetres) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("edmonton", "noisy", "local.relations").translation_m.max, 0.35);
}

// Given perfect odometry, the session confirmed a scan turned 0.14 rad off its true heading on a
// third of its beams, laid it on the map and confirmed a third of the log after it: 1.276 m mean,
// 27.7 m max. The correction gate refuses such a refinement (docs/BENCHMARKS.md, "A correction
// gate"): 0.202 m mean (0.200–0.298 under perturbations of the defaults), 465 of 487 scans
// confirmed.
TEST_F(SessionOnRadishLog, FhwWithPerfectOdometryStaysWithin40CentimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("fhw", "exact").translation_m.mean, 0.4);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
  EXPECT_GT(Summary()["validated"].get<int>(), 400);
}

// Edmonton and acapulco were lost for good: given perfect odometry the session ended 13 m and 24 m
// off on average, because the prior E_max of 0.1 m rejected these lasers' scans at their true
// poses (median EV 0.13–0.16 m) and each unconfirmed refinement walked the pose off. With the laser
// signature in force (500 confirmed scans) and low-overlap scans keeping the prediction, measured
// 2026-11-25: perfect odometry 1.015 m and 1.417 m mean (1.0–4.1 m and 0.7–1.7 m under
// perturbations of the defaults), noisy odometry 1.844 m and 2.698 m (1.8–3.7 m, 1.7–2.7 m).
// With loop closure on by default (2026-11-29): perfect 0.792 m and 0.346 m (0.79–2.31 m,
// 0.33–1.58 m), noisy 0.601 m and 0.739 m (0.58–2.20 m, 0.50–1.86 m). With the correction gate
// and the prediction refined when the rules reject it as given (2026-12-01): perfect 0.773 m and
// 0.196 m (0.63–0.86 m, 0.19–0.45 m), noisy 0.591 m and 0.213 m (0.59–0.70 m, 0.18–0.51 m).
TEST_F(SessionOnRadishLog, EdmontonAndAcapulcoWithPerfectOdometryStayWithinFiveMetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("edmonton", "exact").translation_m.mean, 5.0);
  EXPECT_LT(Run("acapulco", "exact").translation_m.mean, 5.0);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
}

// The odometry learned per log (docs/BENCHMARKS.md, "The odometry learned per log", 2026-12-04):
// the closures show a perfect odometry missing them by their own few millimetres where the
// matched chain missed by decimetres, and the graph follows it; its position noise is told from
// the matching's jitter ("Stretches of four lengths", 2026-12-04, later); its heading noise is
// zero unless the misses reject zero ("An odometry trusted until the misses disprove it",
// 2026-12-05). Issue 15's target for perfect odometry, on all five logs. Measured: seattle 0.006 m
// mean (0.04 m max), orebro 0.038 m (0.17 m), fhw 0.027 m (0.18 m), edmonton 0.007 m (0.05 m),
// acapulco 0.014 m (0.27 m; 0.021 m, 0.25 m since a tighter refinement is kept at its scan 449,
// 2026-12-07; 0.017 m, 0.21 m since the heading test is at 99.9 %, "The heading test at 99.9 %";
// 0.022 m, 0.22 m since a slide still under way is refused, "A laser 1 cm noisier");
// orebro was 0.226 m (1.2 m) before the test, with 3 closures.
TEST_F(SessionOnRadishLog, WithPerfectOdometryEveryLogStaysWithinFiveCmOnAverageAndHalfAMetre) {
  SKIP_WITHOUT_LOGS();
  for (const char* log : {"seattle", "orebro", "fhw", "edmonton", "acapulco"}) {
    const RelationsEvaluation evaluation = Run(log, "exact");
    EXPECT_LT(evaluation.translation_m.mean, 0.05) << log;
    EXPECT_LT(evaluation.translation_m.max, 0.5) << log;
    EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
    const nlohmann::json model = Summary()["loop_closure"]["odometry_model"];
    EXPECT_GE(model["closures"].get<int>(), 1) << log;
    EXPECT_EQ(model["heading_rad2_per_m"].get<double>(), 0.0) << log;
  }
}

TEST_F(SessionOnRadishLog, EdmontonAndAcapulcoWithNoisyOdometryStayWithinFiveMetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("edmonton", "noisy").translation_m.mean, 5.0);
  EXPECT_LT(Run("acapulco", "noisy").translation_m.mean, 5.0);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
}

// Seattle with its perfect odometry as a robot 5 % long in distance and 3 % sharp in its turns
// would report it (scripts/log-variants.py odometry-scale): the session learns both scales from
// its confirmed steps and warns; applied, they hold the map. Measured 2026-12-08: distance ×
// 0.9526, turn × 0.9702 (the odometry's inverses are 0.9524 and 0.9709); applied, 0.084 m mean,
// 0.97 m max; not applied (the default), the map bends at the turns: 1.75 m mean, 6.3 m max.
TEST_F(SessionOnRadishLog, SeattleWithAMiscalibratedOdometryLearnsItsScalesAndHoldsOnThem) {
  SKIP_WITHOUT_LOGS();
  const std::string log =
      Variant("odometry-scale", "seattle", "exact", "seattle-scaled.clf", {"1.05", "1.03"});
  ASSERT_FALSE(log.empty());
  const std::string relations = testing::DatasetsDir() + "/radish/seattle.relations";
  EXPECT_GT(RunOn(log, "seattle-scaled", relations).translation_m.mean, 1.0);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
  // (this run's fits: 0.952 and 0.970 as the map bends)
  EXPECT_NE(run_.err.find("warning: the confirmed scans say the odometry reports distances +5.0 % "
                          "and turns +3."),
            std::string::npos)
      << run_;
  EXPECT_LT(
      RunOn(log, "seattle-applied", relations, {"--set", "session.odometry_calibration_apply=true"})
          .translation_m.mean,
      0.15);
  const nlohmann::json calibration = Summary()["odometry_calibration"];
  EXPECT_TRUE(calibration["applied"].get<bool>());
  EXPECT_NEAR(calibration["distance"]["value"].get<double>(), 1.0 / 1.05, 0.005);
  EXPECT_NEAR(calibration["turn"]["value"].get<double>(), 1.0 / 1.03, 0.005);
  EXPECT_EQ(run_.err.find("warning: the confirmed scans say"), std::string::npos) << run_;
}

// A run whose localised scans were mostly not confirmed (here forced on edmonton by an E_max of
// 1 cm, not learned) must say so, and --strict must make it an error, the run written all the
// same.
TEST_F(SessionOnRadishLog, AMostlyUnconfirmedRunIsWarnedAndAnErrorUnderStrict) {
  SKIP_WITHOUT_LOGS();
  const std::vector<std::string> strict_emax = {"--set", "validation.max_expect_value_m=0.01",
                                                "--set", "session.learned_max_expect_value=false"};
  Run("edmonton", "noisy", "relations", strict_emax);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
  EXPECT_NE(run_.err.find("were not confirmed by the Likelihood Test"), std::string::npos) << run_;
  EXPECT_EQ(Summary()["problem"], "most localised scans were not confirmed by the Likelihood Test");
  std::vector<std::string> args = strict_emax;
  args.insert(args.end(), {"--strict", "--force"});
  Run("edmonton", "noisy", "relations", args);
  EXPECT_TRUE(run_.exited && run_.exit_code != 0) << run_;
  EXPECT_GT(Summary()["iterations"].get<int>(), 300);
}

}  // namespace
}  // namespace scanloc
