// The laser signature: the prior E_max until enough confirmed scans, then median + k · robust σ of
// the remembered expected values, never below the prior; old scans forgotten; histogram distance.

#include "scanloc/likelihood/laser_signature.hpp"

#include <gtest/gtest.h>

namespace scanloc {
namespace {

LikelihoodTestResult Confirmed(double expect_value_m, std::vector<int> histogram = {1, 1}) {
  LikelihoodTestResult t;
  t.valid_pairs = t.match_pairs = 10;
  t.expect_value_m = expect_value_m;
  t.histogram = std::move(histogram);
  return t;
}

TEST(LaserSignature, ThePriorStandsUntilMinSamplesScansWereConfirmed) {
  LaserSignature signature({50, 3, 3.0});
  signature.Add(Confirmed(0.3));
  signature.Add(Confirmed(0.3));
  EXPECT_FALSE(signature.learned());
  EXPECT_DOUBLE_EQ(signature.ExpectValueBound(0.1), 0.1);
  signature.Add(Confirmed(0.3));
  EXPECT_TRUE(signature.learned());
  EXPECT_DOUBLE_EQ(signature.ExpectValueBound(0.1), 0.3);  // no spread: the median
}

TEST(LaserSignature, TheBoundIsTheMedianPlusThreeRobustSigmas) {
  LaserSignature signature({50, 5, 3.0});
  for (const double ev : {0.10, 0.12, 0.14, 0.16, 0.30}) signature.Add(Confirmed(ev));
  // Median 0.14; deviations 0.04 0.02 0 0.02 0.16 → MAD 0.02; 0.14 + 3 · 1.4826 · 0.02.
  EXPECT_NEAR(signature.ExpectValueBound(0.05), 0.14 + 3.0 * 1.4826 * 0.02, 1e-12);
  EXPECT_DOUBLE_EQ(signature.ExpectValueBound(0.5), 0.5);  // never below the prior
}

TEST(LaserSignature, OnlyTheLastWindowScansSpeak) {
  LaserSignature signature({3, 3, 3.0});
  for (int i = 0; i < 10; ++i) signature.Add(Confirmed(0.5));
  for (int i = 0; i < 3; ++i) signature.Add(Confirmed(0.2));
  EXPECT_EQ(signature.samples(), 3u);
  EXPECT_DOUBLE_EQ(signature.ExpectValueBound(0.1), 0.2);
}

TEST(LaserSignature, AScanWithoutMatchPairsTeachesNothing) {
  LaserSignature signature({50, 1, 3.0});
  LikelihoodTestResult empty;
  signature.Add(empty);
  EXPECT_EQ(signature.samples(), 0u);
}

TEST(LaserSignature, HistogramDistanceIsZeroForTheSameShapeAndTwoForDisjoint) {
  LaserSignature signature({50, 1, 3.0});
  signature.Add(Confirmed(0.1, {4, 4, 0, 0}));
  EXPECT_DOUBLE_EQ(signature.HistogramDistance(Confirmed(0.1, {1, 1, 0, 0})), 0.0);
  EXPECT_DOUBLE_EQ(signature.HistogramDistance(Confirmed(0.1, {0, 0, 3, 5})), 2.0);
  EXPECT_EQ(signature.MeanHistogram(), (std::vector<double>{0.5, 0.5, 0.0, 0.0}));
}

TEST(LaserSignatureOptions, AbsurdValuesAreRefused) {
  EXPECT_THROW(LaserSignature({-1, 1, 3.0}), std::invalid_argument);
  EXPECT_THROW(LaserSignature({5, 10, 3.0}), std::invalid_argument);
  EXPECT_THROW(LaserSignature({5, 1, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
