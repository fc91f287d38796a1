// Variance components: three sources of error told apart by comparing them two by two (the
// three-cornered hat), a source no comparison needs found at zero, and a few gross misses that
// do not carry the scales away.

#include "scanloc/graph/variance_components.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace scanloc {
namespace {

// Squared differences of two of three Gaussian sources with variances `sigma2` × `shape`, where
// each observation has its own shape (its length, say), drawn uniformly in [1, 20]; seed 5 unless
// told.
std::vector<VarianceObservation> PairwiseDifferences(const Eigen::Vector3d& sigma2, int per_pair,
                                                     unsigned seed = 5) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> length(1.0, 20.0);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<VarianceObservation> observations;
  for (int pair = 0; pair < 3; ++pair)
    for (int k = 0; k < per_pair; ++k) {
      Eigen::Vector3d design = Eigen::Vector3d::Constant(length(random));
      design(pair) = 0.0;  // the pair is the other two sources
      const double variance = design.dot(sigma2);
      const double miss = std::sqrt(variance) * unit(random);
      observations.push_back({miss * miss, 0.0, design});
    }
  return observations;
}

// A scale is half a sum and two differences of the pairs' variances, each known to √(2/n) of
// itself (a sample variance's σ): with 10,000 pairs of each kind, the smallest, 1e-4, to 6.4 %.
TEST(VarianceComponents, ThreeSourcesComparedTwoByTwoAreEachFoundWithinTwentyPercent) {
  const Eigen::Vector3d sigma2(4e-4, 1e-4, 2.5e-4);
  const Eigen::VectorXd scales = FitVarianceComponents(PairwiseDifferences(sigma2, 10000));
  ASSERT_EQ(scales.size(), 3);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(scales(j), sigma2(j), 0.2 * sigma2(j)) << "source " << j;
}

TEST(VarianceComponents, APerfectSourceIsFoundPerfectWhereTheOthersExplainEveryMiss) {
  const Eigen::Vector3d sigma2(0.0, 1e-4, 3e-4);
  const Eigen::VectorXd scales = FitVarianceComponents(PairwiseDifferences(sigma2, 2000));
  EXPECT_LT(scales(0), 0.02 * sigma2(1));
  EXPECT_NEAR(scales(1), sigma2(1), 0.1 * sigma2(1));
  EXPECT_NEAR(scales(2), sigma2(2), 0.1 * sigma2(2));
}

TEST(VarianceComponents, OneGrossMissInAHundredMovesNoScaleByMoreThanAFifth) {
  const Eigen::Vector3d sigma2(2e-4, 5e-4, 1e-4);
  std::vector<VarianceObservation> observations = PairwiseDifferences(sigma2, 1000);
  for (std::size_t k = 0; k < observations.size(); k += 100)
    observations[k].squared_miss = 1e4 * observations[k].design.dot(sigma2);
  const Eigen::VectorXd scales = FitVarianceComponents(observations);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(scales(j), sigma2(j), 0.2 * sigma2(j)) << "source " << j;
}

TEST(VarianceComponents, AKnownPartIsNotCountedInTheScales) {
  // Every miss is the known part alone: no scale is needed.
  std::vector<VarianceObservation> observations;
  std::mt19937 random(3);
  std::normal_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 3000; ++k) {
    const double miss = 0.01 * unit(random);
    observations.push_back({miss * miss, 1e-4, Eigen::Vector2d(1.0, 2.0)});
  }
  const Eigen::VectorXd scales = FitVarianceComponents(observations);
  ASSERT_EQ(scales.size(), 2);
  EXPECT_LT(scales.maxCoeff(), 5e-6);
  EXPECT_EQ(FitVarianceComponents({}).size(), 0);
}

// The covariance the Fisher information gives the scales is the spread they show over 60 draws
// (seeds 100–159) within a factor of 1.5 in σ.
TEST(VarianceComponents, TheScalesCovarianceIsTheirSpreadOverDrawsWithinHalf) {
  const Eigen::Vector3d sigma2(4e-4, 1e-4, 2.5e-4);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum2 = Eigen::Vector3d::Zero();
  const int draws = 60;
  for (int draw = 0; draw < draws; ++draw) {
    const Eigen::VectorXd scales =
        FitVarianceComponents(PairwiseDifferences(sigma2, 300, 100 + draw));
    sum += scales;
    sum2 += scales.cwiseProduct(scales);
  }
  const Eigen::Vector3d spread = ((sum2 - sum.cwiseProduct(sum) / draws) / (draws - 1)).cwiseSqrt();
  const std::vector<VarianceObservation> observations = PairwiseDifferences(sigma2, 300);
  const Eigen::MatrixXd covariance =
      VarianceComponentsCovariance(observations, FitVarianceComponents(observations));
  for (int j = 0; j < 3; ++j) {
    const double sigma = std::sqrt(covariance(j, j));
    EXPECT_GT(sigma, spread(j) / 1.5) << "source " << j;
    EXPECT_LT(sigma, spread(j) * 1.5) << "source " << j;
  }
}

// Two sources that are only ever seen together: their sum is known, not how it splits.
TEST(VarianceComponents, TwoScalesAlwaysSeenTogetherHaveAVarianceFarBeyondTheirSize) {
  std::vector<VarianceObservation> observations = PairwiseDifferences({1e-4, 1e-4, 1e-4}, 300);
  for (VarianceObservation& o : observations) o.design(1) = o.design(0);
  const Eigen::VectorXd scales = FitVarianceComponents(observations);
  const Eigen::MatrixXd covariance = VarianceComponentsCovariance(observations, scales);
  EXPECT_GT(covariance(0, 0), 1e6 * 1e-4 * 1e-4);
  EXPECT_GT(covariance(1, 1), 1e6 * 1e-4 * 1e-4);
  EXPECT_LT(covariance(2, 2), 1e-4 * 1e-4);  // the third is still seen on its own
}

// Twice the log-likelihood that fitting source 0 gains over the other two fitted alone.
double LikelihoodRatioOfSourceZero(const std::vector<VarianceObservation>& observations) {
  std::vector<VarianceObservation> without = observations;
  for (VarianceObservation& o : without) o.design(0) = 0.0;
  return 2.0 * (VarianceComponentsLogLikelihood(observations, FitVarianceComponents(observations)) -
                VarianceComponentsLogLikelihood(without, FitVarianceComponents(without)));
}

// A perfect source gains less than χ²₁'s 99 % quantile (6.63) with 100 pairs of each kind (0.97;
// 0–0.97 over seeds 5–9); one with twice the next source's variance gains far more with 300 (45;
// 30–74 over those seeds). A source a quarter of the next one's, 2.5e-5, is not told from zero
// with 100 (0–2.6): the test asks for evidence, and few misses give little.
TEST(VarianceComponents, APerfectSourceGainsLessThanChi2sNinetyNinePercentAndANoisyOneFarMore) {
  EXPECT_LT(LikelihoodRatioOfSourceZero(PairwiseDifferences({0.0, 1e-4, 3e-4}, 100)), 6.63);
  EXPECT_GT(LikelihoodRatioOfSourceZero(PairwiseDifferences({2e-4, 1e-4, 3e-4}, 300)), 20.0);
}

TEST(VarianceComponents, TheLogLikelihoodPeaksNearTheScalesThatMadeTheMisses) {
  const Eigen::Vector3d sigma2(2e-4, 1e-4, 3e-4);
  const std::vector<VarianceObservation> observations = PairwiseDifferences(sigma2, 2000);
  const double at_truth = VarianceComponentsLogLikelihood(observations, sigma2);
  EXPECT_GT(at_truth, VarianceComponentsLogLikelihood(observations, 1.3 * sigma2));
  EXPECT_GT(at_truth, VarianceComponentsLogLikelihood(observations, 0.7 * sigma2));
  EXPECT_GT(at_truth,
            VarianceComponentsLogLikelihood(observations, Eigen::Vector3d(0.0, 1e-4, 3e-4)));
}

TEST(VarianceComponents, AWildMissCostsTheLogLikelihoodNoMoreThanItsCap) {
  const VarianceObservation wild{1e6, 0.0, Eigen::Vector2d(1.0, 0.0)};
  const double expected = -0.5 * (std::log(2.0) + 10.828);
  EXPECT_NEAR(VarianceComponentsLogLikelihood({wild}, Eigen::Vector2d(2.0, 5.0)), expected, 1e-12);
  const VarianceObservation two{4.0, 1.0, Eigen::Vector2d(1.0, 0.0), 2.0};  // v = 3, k = 2
  EXPECT_NEAR(VarianceComponentsLogLikelihood({two}, Eigen::Vector2d(2.0, 5.0)),
              -(std::log(3.0) + 4.0 / 3.0), 1e-12);
}

}  // namespace
}  // namespace scanloc
