// A heading correction the tracker made, disputed by the closure tried at the same scan: withdrawn
// only when the closure was validated, holds the prediction's heading and disputes the tracker's.

#include "scanloc/session/turn_dispute.hpp"

#include <gtest/gtest.h>

namespace scanloc {
namespace {

constexpr double kAgreeRad = 0.03;
constexpr double kMinCorrectionRad = 0.09;  // e.g. 0.75 of a gate's 0.12 rad bound

// orebro's noisy scan 213 in the session's frame: the prediction, the tracker's refinement turned
// 0.108 rad from it, and the closure's match on older nodes 0.016 rad from it.
const Pose2D kPrediction{-5.037, -13.493, 2.5915};
const Pose2D kTracked{-4.995, -13.422, 2.6995};

ClosureAttempt PendingClosure(double yaw_rad) {
  ClosureAttempt closure;
  closure.pending = true;
  closure.reason = "pending: 1 of 5 agreeing scans";
  closure.T_world_robot_matched = Pose2D{-4.792, -13.515, yaw_rad};
  return closure;
}

TEST(TurnDispute, AClosureHoldingThePredictionsHeadingWithdrawsALargeTurn) {
  const auto dispute =
      DisputedTurn(kPrediction, kTracked, PendingClosure(2.6072), kMinCorrectionRad, kAgreeRad);
  ASSERT_TRUE(dispute.has_value());
  EXPECT_NEAR(dispute->correction_rad, 0.108, 1e-9);
  EXPECT_NEAR(dispute->closure_from_prediction_rad, 0.0157, 1e-9);
  EXPECT_NEAR(dispute->closure_from_tracked_rad, -0.0923, 1e-9);
  EXPECT_EQ(dispute->T_world_robot_tracked.yaw_rad, kTracked.yaw_rad);
}

TEST(TurnDispute, ATurnWithinTheMinimumCorrectionStands) {
  EXPECT_FALSE(DisputedTurn(kPrediction, kTracked, PendingClosure(2.6072), 0.11, kAgreeRad));
}

TEST(TurnDispute, AClosureOutsideAgreeRadOfThePredictionDisputesNothing) {
  // 0.035 rad from the prediction, 0.073 from the tracker: neither witness agrees with it.
  EXPECT_FALSE(
      DisputedTurn(kPrediction, kTracked, PendingClosure(2.6265), kMinCorrectionRad, kAgreeRad));
}

TEST(TurnDispute, AClosureWithinAgreeRadOfTheTrackerSupportsTheTurn) {
  // With agree_rad 0.1 the closure lies within it of the tracker too: it says nothing against it.
  EXPECT_FALSE(DisputedTurn(kPrediction, kTracked, PendingClosure(2.6072), kMinCorrectionRad, 0.1));
}

TEST(TurnDispute, OnlyAValidatedPendingClosureDisputes) {
  ClosureAttempt rejected = PendingClosure(2.6072);
  rejected.pending = false;
  rejected.reason = "not validated: rule 2";
  EXPECT_FALSE(DisputedTurn(kPrediction, kTracked, rejected, kMinCorrectionRad, kAgreeRad));
  ClosureAttempt accepted = PendingClosure(2.6072);
  accepted.pending = false;
  accepted.accepted = true;  // its solve moved the graph already
  EXPECT_FALSE(DisputedTurn(kPrediction, kTracked, accepted, kMinCorrectionRad, kAgreeRad));
}

TEST(TurnDispute, TheRunsCorrectionBeforeTheClosureIsTheOldFramesDriftNotADispute) {
  // The closures pending before found the old nodes' frame turned by +0.09 rad from the session's:
  // a closure matched at 2.7895 puts the scan at 2.6995 in the session's frame, the tracker's.
  ClosureAttempt closure = PendingClosure(2.7895);
  closure.run_correction = Pose2D{0.0, 0.0, 0.09};
  EXPECT_FALSE(DisputedTurn(kPrediction, kTracked, closure, kMinCorrectionRad, kAgreeRad));
  // Turned by −0.0068 rad (orebro's scan 212): 2.6072 in the old frame is 2.6140 in the session's,
  // 0.0225 rad from the prediction and 0.0855 rad from the tracker.
  closure = PendingClosure(2.6072);
  closure.run_correction = Pose2D{0.0, 0.0, -0.0068};
  const auto dispute = DisputedTurn(kPrediction, kTracked, closure, kMinCorrectionRad, kAgreeRad);
  ASSERT_TRUE(dispute.has_value());
  EXPECT_NEAR(dispute->closure_from_prediction_rad, 0.0225, 1e-9);
  EXPECT_NEAR(dispute->closure_from_tracked_rad, -0.0855, 1e-9);
}

TEST(TurnDispute, HeadingsCompareAcrossTheAngleWrap) {
  const Pose2D prediction{0.0, 0.0, 3.10};
  const Pose2D tracked{0.0, 0.0, -3.05};  // 0.133 rad from the prediction across ±π
  const auto dispute =
      DisputedTurn(prediction, tracked, PendingClosure(3.12), kMinCorrectionRad, kAgreeRad);
  ASSERT_TRUE(dispute.has_value());
  EXPECT_NEAR(dispute->correction_rad, 2.0 * M_PI - 6.15, 1e-9);
}

}  // namespace
}  // namespace scanloc
