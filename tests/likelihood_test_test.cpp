#include "scanloc/likelihood/likelihood_test.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace scanloc {
namespace {

// A real scan and a simulated scan with the given ranges (-1 marks an invalid range).
struct Pair {
  LaserScan scan;
  SimulatedScan simulated;
};
Pair MakePair(const std::vector<double>& real, const std::vector<double>& simulated) {
  Pair p;
  p.scan.layout = MakeLayout(real.size(), M_PI, 20.0);
  p.scan.ranges_m = real;
  p.simulated.layout = p.scan.layout;
  p.simulated.ranges_m = simulated;
  for (const double r : simulated) {
    p.simulated.hit_source.push_back(r > 0 ? HitSource::kSegment : HitSource::kNone);
    p.simulated.hit_index.push_back(r > 0 ? 0 : -1);
  }
  return p;
}

TEST(RunLikelihoodTest, HistogramAndMomentsEqualHandComputedValues) {
  // Distances: 0.004 (slot 0), 0.015 (slot 1), 0.015 (slot 1), 0.195 (last slot: > 0.19),
  // 0.6 (beyond T_Map: valid, not a match), and two invalid pairs.
  const Pair p =
      MakePair({1.004, 2.015, 3.0, 1.195, 2.6, -1.0, 1.0}, {1.0, 2.0, 3.015, 1.0, 2.0, 1.0, -1.0});
  const LikelihoodTestResult r = RunLikelihoodTest(p.scan, p.simulated);
  EXPECT_EQ(r.valid_pairs, 5);
  EXPECT_EQ(r.match_pairs, 4);
  ASSERT_EQ(r.histogram.size(), 20u);
  EXPECT_EQ(r.histogram[0], 1);
  EXPECT_EQ(r.histogram[1], 2);
  EXPECT_EQ(r.histogram[19], 1);
  // (3.9): (0.005 + 2·0.015 + Δmax) / 4 with Δmax = 1.5·20·0.01 = 0.3.
  EXPECT_NEAR(r.expect_value_m, (0.005 + 0.030 + 0.3) / 4.0, 1e-12);
  // (3.10) with t·Δmax²: (0.005² + 2·0.015² + 0.3²) / 4.
  EXPECT_NEAR(r.dispersion_m2, (0.005 * 0.005 + 2 * 0.015 * 0.015 + 0.09) / 4.0, 1e-12);
  EXPECT_NEAR(r.MatchRatio(), 0.8, 1e-12);
}

TEST(RunLikelihoodTest, LastSlotStartsAtNsMinusOneSlots) {
  // 0.185 goes to slot 18, 0.1905 to the last slot (19): step 5 reads > (NS−1)·Δslot.
  const Pair p = MakePair({1.185, 1.1905}, {1.0, 1.0});
  const LikelihoodTestResult r = RunLikelihoodTest(p.scan, p.simulated);
  EXPECT_EQ(r.histogram[18], 1);
  EXPECT_EQ(r.histogram[19], 1);
}

TEST(RunLikelihoodTest, MatchThresholdAndLastSlotDistanceAreHonoured) {
  LikelihoodTestOptions options;
  options.match_threshold_m = 0.4;  // the trials' T_Map
  options.last_slot_distance_m = 0.38;
  const Pair p = MakePair({1.45, 1.35}, {1.0, 1.0});
  const LikelihoodTestResult r = RunLikelihoodTest(p.scan, p.simulated, options);
  EXPECT_EQ(r.valid_pairs, 2);
  EXPECT_EQ(r.match_pairs, 1);
  EXPECT_NEAR(r.expect_value_m, 0.38, 1e-12);
}

TEST(RunLikelihoodTest, NoValidPairGivesZeroMomentsNotNaN) {
  const Pair p = MakePair({-1.0, 5.0}, {1.0, -1.0});
  const LikelihoodTestResult r = RunLikelihoodTest(p.scan, p.simulated);
  EXPECT_EQ(r.valid_pairs, 0);
  EXPECT_EQ(r.match_pairs, 0);
  EXPECT_EQ(r.expect_value_m, 0.0);
  EXPECT_EQ(r.MatchRatio(), 0.0);
}

TEST(RunLikelihoodTest, NanAndInfiniteRangesAreInvalidPairs) {
  const Pair p = MakePair({NAN, INFINITY, 1.0}, {1.0, 1.0, 1.0});
  EXPECT_EQ(RunLikelihoodTest(p.scan, p.simulated).valid_pairs, 1);
}

TEST(RunLikelihoodTest, MismatchedBeamCountsAreRefused) {
  Pair p = MakePair({1.0, 1.0}, {1.0, 1.0});
  p.simulated.ranges_m.pop_back();
  EXPECT_THROW(RunLikelihoodTest(p.scan, p.simulated), std::invalid_argument);
}

TEST(LikelihoodTestOptions, AbsurdValuesAreRefusedWithAMessage) {
  auto refuses = [](auto mutate, const char* needle) {
    LikelihoodTestOptions options;
    mutate(options);
    try {
      options.Validate();
      ADD_FAILURE() << "accepted " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  refuses([](auto& o) { o.slot_count = 1; }, "slot_count");
  refuses([](auto& o) { o.slot_count = -20; }, "slot_count");
  refuses([](auto& o) { o.slot_width_m = 0.0; }, "slot_width_m");
  refuses([](auto& o) { o.slot_width_m = NAN; }, "slot_width_m");
  refuses([](auto& o) { o.match_threshold_m = -0.5; }, "match_threshold_m");
  refuses([](auto& o) { o.last_slot_distance_m = INFINITY; }, "last_slot_distance_m");
  EXPECT_NO_THROW(LikelihoodTestOptions{}.Validate());
}

}  // namespace
}  // namespace scanloc
