#include "scanloc/session/hypothesis_evidence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scanloc/likelihood/candidate_ranking.hpp"

namespace scanloc {
namespace {

Hypothesis WithCosts(std::size_t first_scan, const std::vector<double>& costs) {
  Hypothesis h;
  for (std::size_t i = 0; i < costs.size(); ++i) RecordCost(h, first_scan + i, costs[i]);
  return h;
}

TEST(HypothesisEvidence, ACostHigherAtEveryScanByASteadyMarginIsDecidedAfterThreeScans) {
  const Hypothesis cheaper = WithCosts(10, {0.100, 0.110, 0.095, 0.105});
  const Hypothesis costlier = WithCosts(10, {0.120, 0.131, 0.114, 0.126});
  const CostComparison c = CompareCosts(costlier, cheaper, 3, 0.05);
  EXPECT_EQ(c.scans, 4);
  EXPECT_NEAR(c.mean_excess, 0.02025, 1e-9);
  EXPECT_GT(c.t, StudentT999(3));
  EXPECT_TRUE(c.decided);
  EXPECT_FALSE(CompareCosts(cheaper, costlier, 3, 0.05).decided) << "the test is one-sided";
}

TEST(HypothesisEvidence, DifferencesThatChangeSignAreNotDecided) {
  const Hypothesis a = WithCosts(0, {0.10, 0.13, 0.09, 0.12, 0.10, 0.14, 0.09, 0.12});
  const Hypothesis b = WithCosts(0, {0.12, 0.10, 0.12, 0.10, 0.13, 0.10, 0.12, 0.10});
  EXPECT_FALSE(CompareCosts(a, b, 3, 0.0).decided);
  EXPECT_FALSE(CompareCosts(b, a, 3, 0.0).decided);
}

TEST(HypothesisEvidence, FewerCommonScansThanAskedAreNeverDecided) {
  const Hypothesis cheaper = WithCosts(0, {0.10, 0.10});
  const Hypothesis costlier = WithCosts(0, {0.20, 0.20});
  EXPECT_FALSE(CompareCosts(costlier, cheaper, 3, 0.05).decided);
  EXPECT_TRUE(CompareCosts(costlier, cheaper, 2, 0.05).decided)
      << "a constant excess has no spread";
}

TEST(HypothesisEvidence, OnlyTheScansBothWereLocalisedAtArePaired) {
  // `late` was found at scan 5; the older one's far lower costs before that do not count.
  const Hypothesis old = WithCosts(0, {0.01, 0.01, 0.01, 0.01, 0.01, 0.20, 0.21, 0.19, 0.20});
  const Hypothesis late = WithCosts(5, {0.10, 0.11, 0.09, 0.10});
  const CostComparison c = CompareCosts(old, late, 3, 0.05);
  EXPECT_EQ(c.scans, 4);
  EXPECT_NEAR(c.mean_excess, 0.10, 1e-9);
  EXPECT_TRUE(c.decided);
}

TEST(HypothesisEvidence, ASteadyExcessOfAFewPercentIsNotDecided) {
  // A refinement settled a little off its place's best fit: 3 % costlier at every scan.
  const Hypothesis cheaper = WithCosts(0, {0.100, 0.110, 0.095, 0.105, 0.100, 0.102});
  const Hypothesis costlier = WithCosts(0, {0.1031, 0.1132, 0.0980, 0.1081, 0.1030, 0.1051});
  const CostComparison c = CompareCosts(costlier, cheaper, 3, 0.05);
  EXPECT_GT(c.t, StudentT999(c.scans - 1)) << "beyond chance";
  EXPECT_FALSE(c.decided) << "but by 3 %, under the 5 % asked";
  EXPECT_TRUE(CompareCosts(costlier, cheaper, 3, 0.02).decided);
}

TEST(HypothesisEvidence, TheHistoryKeepsTheNewestCostsAndSkipsScansWithoutOne) {
  Hypothesis h;
  for (std::size_t scan = 0; scan < 3 * kMaxCostHistory; ++scan)
    RecordCost(h, scan, static_cast<double>(scan));
  RecordCost(h, 3 * kMaxCostHistory, std::nan(""));
  ASSERT_EQ(h.costs.size(), kMaxCostHistory);
  EXPECT_EQ(h.costs.front().scan, 2 * kMaxCostHistory);
  EXPECT_EQ(h.costs.back().scan, 3 * kMaxCostHistory - 1);
  RecordCost(h, 3 * kMaxCostHistory - 1, 0.5);  // the same scan again: replaced, not added
  EXPECT_EQ(h.costs.size(), kMaxCostHistory);
  EXPECT_DOUBLE_EQ(h.costs.back().cost, 0.5);
}

Hypothesis Held(double cost, double truncated_mean_m, bool validated = true) {
  Hypothesis h;
  h.cost = cost;
  h.truncated_mean_m = truncated_mean_m;
  h.validated = validated;
  h.verdict = validated ? Verdict::kValid : Verdict::kLowMatchRatio;
  return h;
}

TEST(HypothesisEvidence, Rule3AmongHeldHypothesesCountsOnlyWhereTheTruncatedMeanAgrees) {
  // A corridor look-alike matching fewer beams tightly: the cheapest by (3.11) (0.060). The
  // true place costs 0.095 (> 1.5 × 0.060) but has the lower truncated mean; a third costs
  // 0.100 with a higher truncated mean too; a fourth stays within rule 3 (0.085); a fifth was
  // not validated at all.
  std::vector<Hypothesis> held{Held(0.060, 0.160), Held(0.095, 0.138), Held(0.100, 0.190),
                               Held(0.085, 0.170), Held(0.300, 0.400, false)};
  std::vector<Hypothesis> plain = held;
  const std::vector<bool> counts = JudgeRelativeCost(held, 1.5, true);
  EXPECT_EQ(counts, (std::vector<bool>{true, false, true, true, true}));
  EXPECT_TRUE(held[0].validated);
  EXPECT_FALSE(held[1].validated) << "not validated at this scan, whatever counts";
  EXPECT_EQ(held[1].verdict, Verdict::kHighCost);
  EXPECT_EQ(held[2].verdict, Verdict::kHighCost);
  EXPECT_TRUE(held[3].validated);
  EXPECT_EQ(held[4].verdict, Verdict::kLowMatchRatio) << "its own rule stays its reason";
  // Without the truncated mean's word, every rejection counts.
  EXPECT_EQ(JudgeRelativeCost(plain, 1.5, false), std::vector<bool>(5, true));
  EXPECT_EQ(plain[1].verdict, Verdict::kHighCost);
  // None validated: nothing to compare with, nothing changes.
  std::vector<Hypothesis> none{Held(0.1, 0.2, false), Held(0.5, 0.1, false)};
  EXPECT_EQ(JudgeRelativeCost(none, 1.5, true), std::vector<bool>(2, true));
  EXPECT_EQ(none[1].verdict, Verdict::kLowMatchRatio);
}

LikelihoodTestResult TestOf(int valid_pairs, int match_pairs, double expect_value_m) {
  LikelihoodTestResult test;
  test.valid_pairs = valid_pairs;
  test.match_pairs = match_pairs;
  test.expect_value_m = expect_value_m;
  return test;
}

TEST(HypothesisEvidence, TheTruncatedMeanCountsEachUnmatchedPairAsTMap) {
  // 150 pairs matched at 0.1 m on average and 50 beyond T_Map = 0.5 m.
  EXPECT_NEAR(TruncatedMeanDistance(TestOf(200, 150, 0.1), 0.5), (150 * 0.1 + 50 * 0.5) / 200,
              1e-12);
  EXPECT_NEAR(TruncatedMeanDistance(TestOf(10, 0, 0.0), 0.5), 0.5, 1e-12);
  EXPECT_TRUE(std::isinf(TruncatedMeanDistance(TestOf(0, 0, 0.0), 0.5)));
}

TEST(HypothesisEvidence, APlaceThatLeavesLoosePairsUnmatchedIsNotCheaperThanOneThatMatchesThem) {
  // Intel, a localise run on a loop-closed map (docs/BENCHMARKS.md): the true place matched 91 %
  // of the pairs at 0.145 m, a look-alike 24 m away 63 % at 0.107 m.
  const LikelihoodTestResult truth = TestOf(180, 164, 0.145);
  const LikelihoodTestResult look_alike = TestOf(180, 113, 0.107);
  EXPECT_LT(LikelihoodCost(look_alike, 0.1), LikelihoodCost(truth, 0.1)) << "(3.11) prefers it";
  EXPECT_LT(TruncatedMeanDistance(truth, 0.5), 0.8 * TruncatedMeanDistance(look_alike, 0.5));
}

// A hypothesis with its costs at consecutive scans from `first_scan`, validated at all of them.
Hypothesis Held(std::size_t first_scan, const std::vector<double>& costs) {
  Hypothesis h = WithCosts(first_scan, costs);
  h.validated = true;
  h.confirmations = h.confirmed_in_row = static_cast<int>(costs.size());
  h.truncated_mean_m = costs.back();
  return h;
}

TEST(HypothesisEvidence, ThePlaceCheaperAtTheScansBothWereTestedAtRanksFirstNotTheOlder) {
  // Like ACES's splice on the default map (docs/BENCHMARKS.md): a look-alike found first, and the
  // true place found four scans later, cheaper at every scan since.
  const Hypothesis older = Held(281, {0.257, 0.262, 0.265, 0.269, 0.261, 0.259, 0.268, 0.271});
  const Hypothesis truth = Held(285, {0.246, 0.234, 0.240, 0.243});
  const std::size_t since = CommonSince({older, truth});
  EXPECT_EQ(since, 285u);
  EXPECT_TRUE(RanksBefore(truth, older, since));
  EXPECT_FALSE(RanksBefore(older, truth, since));
  // Before the newer one was costed twice, the one validated at more scans leads, as before.
  const Hypothesis found = Held(288, {0.243});
  const std::size_t just = CommonSince({older, truth, found});
  EXPECT_EQ(just, std::numeric_limits<std::size_t>::max()) << "one was costed once only";
  EXPECT_TRUE(RanksBefore(older, found, just));
  EXPECT_TRUE(RanksBefore(older, truth, just)) << "the same order for every pair";
}

TEST(HypothesisEvidence, APlaceValidatedAtTheLastScanOrAtMoreCommonScansRanksFirstWhateverItCosts) {
  Hypothesis cheap = Held(10, {0.10, 0.10, 0.10, 0.10});
  const Hypothesis costly = Held(10, {0.20, 0.20, 0.20, 0.20});
  cheap.validated = false;
  cheap.confirmed_in_row = 0;
  EXPECT_TRUE(RanksBefore(costly, cheap, CommonSince({cheap, costly})));
  cheap.validated = true;
  cheap.confirmed_in_row = 1;  // validated at the last scan only, the other at all four
  EXPECT_TRUE(RanksBefore(costly, cheap, CommonSince({cheap, costly})));
  cheap.confirmed_in_row = 4;
  EXPECT_TRUE(RanksBefore(cheap, costly, CommonSince({cheap, costly})));
  EXPECT_EQ(CommonSince({cheap, Hypothesis{}}), std::numeric_limits<std::size_t>::max())
      << "a hypothesis not costed yet leaves no common scans";
}

TEST(HypothesisEvidence, TheOutputStaysWithTheHypothesisItFollowedUntilAnotherIsClearlyCheaper) {
  // ACES's corridors (docs/BENCHMARKS.md): the true place and a look-alike 19 m away tie within
  // a few percent for a hundred scans, and the best ranked changes from scan to scan.
  Hypothesis look_alike = Held(20, {0.138, 0.131, 0.140, 0.136});
  Hypothesis followed = Held(20, {0.142, 0.137, 0.139, 0.145});  // 2.9 % costlier
  look_alike.T_world_robot = {23.5, -8.4, -1.50};
  followed.T_world_robot = {6.05, -0.14, -0.08};
  const Pose2D output_before{6.00, -0.10, -0.07};  // carried by the odometry to this scan
  EXPECT_EQ(SteadyOutput({look_alike, followed}, output_before, 0.3, 0.1, 0.1), 1u);
  // Another hypothesis far from the output before changes nothing; a near one that is not it
  // (0.25 m off) is not taken when the followed one is nearer.
  Hypothesis beside = followed;
  beside.T_world_robot = {6.25, -0.10, -0.07};
  EXPECT_EQ(SteadyOutput({look_alike, beside, followed}, output_before, 0.3, 0.1, 0.1), 2u);
  // The best ranked 10 % cheaper or more at the common scans: the output goes to it.
  Hypothesis costlier = Held(20, {0.152, 0.145, 0.155, 0.150});  // 10.3 % costlier
  costlier.T_world_robot = followed.T_world_robot;
  EXPECT_EQ(SteadyOutput({look_alike, costlier}, output_before, 0.3, 0.1, 0.1), 0u);
  // Not validated at this scan, too far from the output before, or already the best: the best.
  Hypothesis failed = followed;
  failed.validated = false;
  EXPECT_EQ(SteadyOutput({look_alike, failed}, output_before, 0.3, 0.1, 0.1), 0u);
  EXPECT_EQ(SteadyOutput({look_alike, followed}, {6.0, -0.5, -0.07}, 0.3, 0.1, 0.1), 0u);
  EXPECT_EQ(SteadyOutput({look_alike, followed}, {6.0, -0.1, 0.2}, 0.3, 0.1, 0.1), 0u);
  EXPECT_EQ(SteadyOutput({followed, look_alike}, output_before, 0.3, 0.1, 0.1), 0u);
}

// A hypothesis localised at consecutive scans from `first_scan` with these truncated means,
// expected values and match ratios.
Hypothesis WithSeries(std::size_t first_scan, const std::vector<double>& truncated_means,
                      const std::vector<double>& expect_values,
                      const std::vector<double>& match_ratios) {
  Hypothesis h;
  for (std::size_t i = 0; i < truncated_means.size(); ++i)
    RecordCost(h, first_scan + i, truncated_means[i], expect_values[i], match_ratios[i]);
  return h;
}

TEST(HypothesisEvidence, APlaceMatchingItsPairsFarTighterAndNoDearerOutmatchesTheOther) {
  // ACES's alike corridors on a loop-closed map (docs/BENCHMARKS.md): the true place matches as
  // many pairs 30 % tighter and costs 6 % less by the truncated mean, which alone decides
  // nothing.
  const Hypothesis truth =
      WithSeries(40, {0.136, 0.140, 0.131, 0.138, 0.142}, {0.041, 0.046, 0.039, 0.044, 0.048},
                 {0.795, 0.805, 0.790, 0.800, 0.801});
  const Hypothesis look_alike =
      WithSeries(40, {0.146, 0.148, 0.141, 0.145, 0.150}, {0.062, 0.066, 0.058, 0.061, 0.069},
                 {0.800, 0.812, 0.794, 0.808, 0.799});
  EXPECT_FALSE(CompareCosts(look_alike, truth, 3, 0.1).decided) << "6 % is inside the margin";
  EXPECT_TRUE(Outmatched(look_alike, truth, 3, 0.1));
  EXPECT_FALSE(Outmatched(truth, look_alike, 3, 0.1));
  EXPECT_FALSE(Outmatched(look_alike, truth, 6, 0.1)) << "fewer common scans than asked";
  // A place 7 m along the corridor matching fewer pairs tighter: its truncated mean is the
  // higher, so it outmatches nothing however much tighter it matches.
  const Hypothesis along =
      WithSeries(40, {0.156, 0.161, 0.152, 0.158, 0.160}, {0.030, 0.034, 0.029, 0.031, 0.035},
                 {0.720, 0.715, 0.722, 0.718, 0.716});
  EXPECT_FALSE(Outmatched(truth, along, 3, 0.1));
  // Twins a few percent apart in both: nothing.
  const Hypothesis twin =
      WithSeries(40, {0.139, 0.143, 0.134, 0.141, 0.145}, {0.043, 0.048, 0.040, 0.046, 0.050},
                 {0.794, 0.803, 0.791, 0.799, 0.800});
  EXPECT_FALSE(Outmatched(twin, truth, 3, 0.1));
  EXPECT_FALSE(CompareSeries(twin, truth, &CostAt::expect_value_m, 3, 0.1).decided);
}

TEST(HypothesisEvidence, ALowerTruncatedMeanIsNoEvidenceAgainstAPlaceThatMatchedTighter) {
  // On one harness map the true place's truncated mean was 13 % above a look-alike's (it matched
  // fewer pairs, each far tighter): decided by the truncated mean, contradicted by the expected
  // value.
  const Hypothesis truth =
      WithSeries(30, {0.170, 0.176, 0.168, 0.173, 0.171}, {0.040, 0.044, 0.041, 0.043, 0.042},
                 {0.720, 0.716, 0.724, 0.719, 0.721});
  const Hypothesis look_alike =
      WithSeries(30, {0.150, 0.155, 0.148, 0.152, 0.151}, {0.062, 0.066, 0.060, 0.065, 0.063},
                 {0.810, 0.806, 0.812, 0.809, 0.811});
  EXPECT_TRUE(CompareCosts(truth, look_alike, 3, 0.1).decided);
  EXPECT_TRUE(MatchedTighter(truth, look_alike, 3, 0.1));
  EXPECT_FALSE(MatchedTighter(look_alike, truth, 3, 0.1));
  EXPECT_FALSE(Outmatched(truth, look_alike, 3, 0.1)) << "its truncated mean is the higher";
}

TEST(HypothesisEvidence, StudentQuantilesFallTowardTheNormalOne) {
  EXPECT_NEAR(StudentT999(1), 318.31, 0.01);
  EXPECT_NEAR(StudentT999(4), 7.173, 1e-3);
  EXPECT_NEAR(StudentT999(30), 3.385, 1e-3);
  EXPECT_NEAR(StudentT999(1000), 3.090, 1e-3);
  EXPECT_TRUE(std::isinf(StudentT999(0)));
}

}  // namespace
}  // namespace scanloc
