// The five sparse Radish logs of other buildings (../shared/datasets/radish, see its README):
// a regression guard for the default session on logs it was not tuned on. Where the default
// session holds, its accuracy is asserted; where it does not yet (acapulco with noisy odometry:
// issue 15), the run must say so loudly. Skips when the logs are absent (in CI they are present).

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

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
    out_ = dir_ + "/" + name + "-" + kind;
    std::vector<std::string> args = {"session", "--log", radish + name + "." + kind + ".clf.gz",
                                     "--out",   out_,    "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    run_ = testing::RunScanloc(args, dir_);
    return EvaluateRelations(ReadTumTrajectory(out_ + "/trajectory.tum"),
                             ReadRelations(radish + name + "." + relations));
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

// Measured 2026-11-25: 0.261 m mean (0.26–0.31 under perturbations of the defaults) with the
// log's 32.76 m no-return code recognised (1.909 m when its readings were phantom walls).
TEST_F(SessionOnRadishLog, OrebroWithItsOwnNoReturnCodeStaysWithin35CentimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("orebro", "noisy").translation_m.mean, 0.35);
  EXPECT_NEAR(Summary()["no_return_m"].get<double>(), 32.76, 0.01);
}

// Measured 2026-11-25: 0.378 m mean (0.31–0.38 under perturbations); the log has PARAM lines of
// five and six fields.
TEST_F(SessionOnRadishLog, FhwWithBothParamFormsStaysWithin45CentimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("fhw", "noisy").translation_m.mean, 0.45);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
}

// Given perfect odometry, the session once ended 13 m (edmonton) and 24 m (acapulco) off on
// average: the prior E_max of 0.1 m rejected the scans of these lasers at their true poses (median
// EV 0.13–0.16 m) and each unconfirmed refinement walked the pose off. With the laser signature in
// force and low-overlap scans keeping the prediction, measured 2026-11-25: edmonton 1.001 m mean
// and acapulco 1.050 m (1.0–2.9 m and 1.05–1.9 m under perturbations of the defaults).
TEST_F(SessionOnRadishLog, EdmontonAndAcapulcoWithPerfectOdometryStayWithinThreeMetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("edmonton", "exact").translation_m.mean, 3.0);
  EXPECT_LT(Run("acapulco", "exact").translation_m.mean, 3.0);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
}

// Acapulco with noisy odometry: the default session leaves most of its scans unconfirmed (issue
// 15; 199 of 861 confirmed, measured 2026-11-25); it must say so, and --strict must make it an
// error, the run written all the same.
TEST_F(SessionOnRadishLog, AcapulcoMostlyUnconfirmedIsWarnedAndAnErrorUnderStrict) {
  SKIP_WITHOUT_LOGS();
  Run("acapulco", "noisy");
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
  EXPECT_NE(run_.err.find("were not confirmed by the Likelihood Test"), std::string::npos) << run_;
  EXPECT_EQ(Summary()["problem"], "most localised scans were not confirmed by the Likelihood Test");
  Run("acapulco", "noisy", "relations", {"--strict", "--force"});
  EXPECT_TRUE(run_.exited && run_.exit_code != 0) << run_;
  EXPECT_GT(Summary()["iterations"].get<int>(), 800);
}

}  // namespace
}  // namespace scanloc
