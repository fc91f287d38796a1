#include "scanloc/likelihood/candidate_ranking.hpp"

#include <gtest/gtest.h>

namespace scanloc {
namespace {

LikelihoodTestResult Moments(int nvp, int mp, double ev, double disp) {
  LikelihoodTestResult t;
  t.valid_pairs = nvp;
  t.match_pairs = mp;
  t.expect_value_m = ev;
  t.dispersion_m2 = disp;
  return t;
}

TEST(RankCandidates, ChapterTable1KeepsOnlyP0) {
  // Table 1 of the chapter (NVP 1749): p0 valid; p1 and p2 fail rule 1 or 2; p3 fails rule 2,
  // with the chapter's E_max of 0.05 m.
  ValidationOptions chapter;
  chapter.max_expect_value_m = 0.05;
  const auto ranking =
      RankCandidates({Moments(1749, 1458, 0.0289, 0.0019), Moments(1749, 900, 0.0496, 0.0060),
                      Moments(1749, 676, 0.0414, 0.0050), Moments(1749, 1276, 0.0641, 0.0080)},
                     chapter);
  EXPECT_EQ(ranking.best, 0);
  EXPECT_EQ(ranking.candidates[0].verdict, Verdict::kValid);
  EXPECT_EQ(ranking.candidates[3].verdict, Verdict::kHighExpectValue);
  EXPECT_EQ(ranking.valid_order, std::vector<int>{0});
}

TEST(RankCandidates, Rule1RejectsLowMatchRatioAndAcceptsAboveIt) {
  ValidationOptions options;
  options.min_match_ratio = 0.3;
  const auto r =
      RankCandidates({Moments(100, 30, 0.02, 0.001), Moments(100, 31, 0.02, 0.001)}, options);
  EXPECT_EQ(r.candidates[0].verdict, Verdict::kLowMatchRatio);  // 0.30 is not > 0.3
  EXPECT_EQ(r.candidates[1].verdict, Verdict::kValid);
  options.min_match_ratio = 0.2;  // the factory's relaxed ratio
  EXPECT_EQ(RankCandidates({Moments(100, 25, 0.02, 0.001)}, options).candidates[0].verdict,
            Verdict::kValid);
}

TEST(RankCandidates, Rule2RejectsHighExpectValueAndAcceptsBelowIt) {
  ValidationOptions options;
  options.max_expect_value_m = 0.05;  // the chapter's E_max
  const auto r =
      RankCandidates({Moments(100, 90, 0.05, 0.003), Moments(100, 90, 0.0499, 0.003)}, options);
  EXPECT_EQ(r.candidates[0].verdict, Verdict::kHighExpectValue);
  EXPECT_EQ(r.candidates[1].verdict, Verdict::kValid);
}

TEST(RankCandidates, ACandidatesOwnExpectValueBoundDecidesRule2ForItAndZeroMeansTheOptions) {
  ValidationOptions options;
  options.max_expect_value_m = 0.10;
  const std::vector<LikelihoodTestResult> tests{
      Moments(100, 90, 0.12, 0.003), Moments(100, 90, 0.12, 0.003), Moments(100, 90, 0.09, 0.003)};
  const auto r = RankCandidates(tests, options, {0.15, 0.0, 0.08});
  EXPECT_EQ(r.candidates[0].verdict, Verdict::kValid) << "its place's 0.15 m, not 0.10 m";
  EXPECT_EQ(r.candidates[1].verdict, Verdict::kHighExpectValue) << "0: the options' 0.10 m";
  EXPECT_EQ(r.candidates[2].verdict, Verdict::kHighExpectValue) << "its own 0.08 m";
  EXPECT_EQ(RankCandidates(tests, options).candidates[0].verdict, Verdict::kHighExpectValue);
  EXPECT_THROW(RankCandidates(tests, options, {0.15}), std::invalid_argument);
}

TEST(RankCandidates, Rule3RejectsMuchHigherCostAndKeepsCloseCost) {
  // Costs (α = 0.1): 0.02 + 0.1·0.1 = 0.030; 0.040 + 0.1·0.3 = 0.070 (> 1.5·0.030);
  // 0.034 + 0.1·0.1 = 0.044 (< 1.5·0.030 = 0.045, kept).
  const auto r = RankCandidates({Moments(100, 90, 0.020, 0.001), Moments(100, 70, 0.040, 0.002),
                                 Moments(100, 90, 0.034, 0.002)});
  EXPECT_NEAR(r.candidates[0].cost, 0.030, 1e-12);
  EXPECT_EQ(r.candidates[1].verdict, Verdict::kHighCost);
  EXPECT_EQ(r.candidates[2].verdict, Verdict::kValid);
  EXPECT_EQ(r.valid_order, (std::vector<int>{0, 2}));
}

TEST(Preferred, Rule4ExpectValueDecidesWhenMatchPairsAreClose) {
  ValidationOptions options;
  CandidateAssessment a, b;
  a.test = Moments(1000, 900, 0.020, 0.0010);  // slightly fewer match pairs, clearly lower EV
  b.test = Moments(1000, 905, 0.030, 0.0009);
  a.cost = LikelihoodCost(a.test, options.alpha_m);
  b.cost = LikelihoodCost(b.test, options.alpha_m);
  EXPECT_TRUE(Preferred(a, b, options));
  EXPECT_FALSE(Preferred(b, a, options));
}

TEST(Preferred, Rule4WeighsBothMomentsWhenMatchPairsDifferClearly) {
  ValidationOptions options;
  CandidateAssessment a, b;
  a.test = Moments(1000, 600, 0.020, 0.0010);  // lower EV but many fewer match pairs
  b.test = Moments(1000, 900, 0.022, 0.0011);
  a.cost = LikelihoodCost(a.test, options.alpha_m);  // 0.020 + 0.04 = 0.060
  b.cost = LikelihoodCost(b.test, options.alpha_m);  // 0.022 + 0.01 = 0.032
  EXPECT_FALSE(Preferred(a, b, options));
  EXPECT_TRUE(Preferred(b, a, options));
}

TEST(Preferred, Rule5DispersionDecidesWhenExpectValuesAreClose) {
  ValidationOptions options;
  CandidateAssessment a, b;
  a.test = Moments(1000, 900, 0.0250, 0.0020);
  b.test = Moments(1000, 900, 0.0249, 0.0010);  // same MP, EV within 0.4 %, half the dispersion
  a.cost = LikelihoodCost(a.test, options.alpha_m);
  b.cost = LikelihoodCost(b.test, options.alpha_m);
  EXPECT_TRUE(Preferred(b, a, options));
  a.test.dispersion_m2 = 0.00101;  // dispersions as close as the EVs: the EV decides again
  EXPECT_TRUE(Preferred(b, a, options));
  b.test.expect_value_m = 0.0251;
  b.cost = LikelihoodCost(b.test, options.alpha_m);
  EXPECT_TRUE(Preferred(a, b, options));
}

TEST(RankCandidates, NoValidPairsIsReportedNotRanked) {
  const auto r = RankCandidates({Moments(0, 0, 0.0, 0.0)});
  EXPECT_EQ(r.candidates[0].verdict, Verdict::kNoValidPairs);
  EXPECT_EQ(r.best, -1);
  EXPECT_TRUE(RankCandidates({}).valid_order.empty());
}

TEST(ValidationOptions, AbsurdValuesAreRefused) {
  ValidationOptions o;
  o.min_match_ratio = 1.5;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = {};
  o.max_cost_ratio = 0.5;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = {};
  o.max_expect_value_m = -1.0;
  EXPECT_THROW(RankCandidates({}, o), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
