// The five sparse Radish logs of other buildings (../shared/datasets/radish, see its README):
// a regression guard for the default session on logs it was not tuned on. Where the default
// session holds, its accuracy is asserted; where it does not yet (edmonton, acapulco: issue 15),
// the run must say so loudly. Skips when the logs are absent (in CI they are present).

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

// Measured 2026-11-23: 0.193 m mean with the log's 32.76 m no-return code recognised (1.909 m
// when its readings were phantom walls).
TEST_F(SessionOnRadishLog, OrebroWithItsOwnNoReturnCodeStaysWithin25CentimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("orebro", "noisy").translation_m.mean, 0.25);
  EXPECT_NEAR(Summary()["no_return_m"].get<double>(), 32.76, 0.01);
}

// Measured 2026-11-23: 0.331 m mean; the log has PARAM lines of five and six fields.
TEST_F(SessionOnRadishLog, FhwWithBothParamFormsStaysWithin40CentimetresOnAverage) {
  SKIP_WITHOUT_LOGS();
  EXPECT_LT(Run("fhw", "noisy").translation_m.mean, 0.4);
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
}

// Edmonton: the default session is lost for most of the log (issue 15); it must say so, and
// --strict must make it an error, the run written all the same.
TEST_F(SessionOnRadishLog, EdmontonMostlyUnconfirmedIsWarnedAndAnErrorUnderStrict) {
  SKIP_WITHOUT_LOGS();
  Run("edmonton", "noisy");
  EXPECT_TRUE(run_.exited && run_.exit_code == 0) << run_;
  EXPECT_NE(run_.err.find("were not confirmed by the Likelihood Test"), std::string::npos) << run_;
  EXPECT_EQ(Summary()["problem"], "most localised scans were not confirmed by the Likelihood Test");
  Run("edmonton", "noisy", "relations", {"--strict", "--force"});
  EXPECT_TRUE(run_.exited && run_.exit_code != 0) << run_;
  EXPECT_GT(Summary()["iterations"].get<int>(), 300);
}

}  // namespace
}  // namespace scanloc
