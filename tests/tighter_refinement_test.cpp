// Among a scan's valid refinements, one that matched more of the scan at a lower truncated mean
// distance is kept where the rules' best won (3.11) by pushing its loose pairs beyond T_Map.

#include "scanloc/session/tighter_refinement.hpp"

#include <gtest/gtest.h>

namespace scanloc {
namespace {

constexpr double kMatchThresholdM = 0.5;  // T_Map
constexpr double kOverlapFraction = 0.75;

RankedCandidate Refined(const char* label, double yaw_rad, int valid_pairs, int match_pairs,
                        double expect_value_m, int rank) {
  RankedCandidate refined;
  refined.candidate.label = label;
  refined.T_world_robot = Pose2D{-33.3, 8.7, yaw_rad};
  refined.test.valid_pairs = valid_pairs;
  refined.test.match_pairs = match_pairs;
  refined.test.expect_value_m = expect_value_m;
  refined.rank = rank;
  refined.verdict = rank >= 0 ? Verdict::kValid : Verdict::kLowMatchRatio;
  return refined;
}

// Acapulco's noisy scan 296 as recorded: the rules ranked first the refinement from −5°, 5.2° off
// the others and 4.3° off the truth, which matched 56 of 153 pairs (EV 0.098 m, truncated mean
// 0.353 m). The prediction's refinement matched 117 of 158 (EV 0.147 m, 0.239 m), the one from +5°
// 119 of 158 (EV 0.149 m, 0.236 m).
LocalisationResult Scan296() {
  LocalisationResult result;
  result.refined = {Refined("odometry", 0.8112, 158, 117, 0.1469, 1),
                    Refined("odometry-5deg", 0.7211, 153, 56, 0.0985, 0),
                    Refined("odometry+5deg", 0.8126, 158, 119, 0.1493, 2)};
  result.best_refined = 1;
  result.kept = 1;
  return result;
}

TEST(TighterRefinement, KeepsTheLowestTruncatedMeanAmongThoseThatMatchedMoreThanTheRulesBest) {
  LocalisationResult result = Scan296();
  EXPECT_EQ(TighterRefinement(result, kMatchThresholdM, kOverlapFraction), 2);
  EXPECT_EQ(KeepTighterRefinement(result, kMatchThresholdM, kOverlapFraction), 1);
  EXPECT_EQ(result.kept, 2);
  EXPECT_EQ(result.best_refined, 2);
  ASSERT_NE(result.Kept(), nullptr);
  EXPECT_EQ(result.Kept()->candidate.label, "odometry+5deg");
  // The kept one ranks first; the others valid keep their order after it.
  EXPECT_EQ(result.refined[2].rank, 0);
  EXPECT_EQ(result.refined[1].rank, 1);
  EXPECT_EQ(result.refined[0].rank, 2);
}

TEST(TighterRefinement, OneMatchingMoreButWithinTheOverlapFractionOutranksNothing) {
  // Acapulco's scan 332 in a variant: 0.89 against 0.90 of the pairs, 0.9° apart. Choosing by the
  // truncated mean there was right as often as wrong.
  LocalisationResult result;
  result.refined = {Refined("odometry", 0.10, 160, 142, 0.137, 0),
                    Refined("odometry+5deg", 0.116, 160, 144, 0.141, 1)};
  result.best_refined = 0;
  result.kept = 0;
  EXPECT_EQ(KeepTighterRefinement(result, kMatchThresholdM, kOverlapFraction), -1);
  EXPECT_EQ(result.kept, 0);
  EXPECT_EQ(result.refined[0].rank, 0);
  EXPECT_EQ(result.refined[1].rank, 1);
}

TEST(TighterRefinement, OneMatchingMoreAtAHigherTruncatedMeanOutranksNothing) {
  // 0.6 of the pairs at 0.45 m (truncated mean 0.47 m) against 0.4 at 0.05 m (0.32 m).
  LocalisationResult result;
  result.refined = {Refined("odometry", 0.0, 100, 40, 0.05, 0),
                    Refined("odometry-5deg", -0.087, 100, 60, 0.45, 1)};
  result.best_refined = 0;
  result.kept = 0;
  EXPECT_EQ(TighterRefinement(result, kMatchThresholdM, kOverlapFraction), -1);
}

TEST(TighterRefinement, ARefinementTheRulesRejectedNeverOutranks) {
  LocalisationResult result = Scan296();
  result.refined[0].rank = -1;
  result.refined[0].verdict = Verdict::kHighCost;
  result.refined[2].rank = -1;
  result.refined[2].verdict = Verdict::kHighCost;
  result.refined[1].rank = 0;
  EXPECT_EQ(KeepTighterRefinement(result, kMatchThresholdM, kOverlapFraction), -1);
  EXPECT_EQ(result.kept, 1);
}

TEST(TighterRefinement, WithoutAValidRefinementNothingChanges) {
  LocalisationResult result = Scan296();
  for (RankedCandidate& refined : result.refined) {
    refined.rank = -1;
    refined.verdict = Verdict::kHighExpectValue;
  }
  result.best_refined = -1;
  result.kept = 1;  // the cheapest, kept as the flagged guess
  EXPECT_EQ(KeepTighterRefinement(result, kMatchThresholdM, kOverlapFraction), -1);
  EXPECT_EQ(result.kept, 1);
  EXPECT_EQ(result.best_refined, -1);
}

}  // namespace
}  // namespace scanloc
