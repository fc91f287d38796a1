// The correction gate: the odometry's error learned from the confirmed scans' corrections; a
// refinement far beyond it on little overlap is refused, unless the next scan agrees with it.

#include "scanloc/session/correction_gate.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace scanloc {
namespace {

// Ten confirmed scans corrected by 0.02 m and 0.005 rad, with 80 % of their beams matched.
CorrectionGate Learned(CorrectionGateOptions options = {}) {
  options.min_samples = 10;
  CorrectionGate gate(options);
  for (int i = 0; i < 10; ++i) gate.Add(Pose2D{0.02, 0.0, i % 2 ? 0.005 : -0.005}, 0.8);
  return gate;
}

TEST(CorrectionGate, NothingIsBoundedBeforeMinSamplesConfirmedScans) {
  CorrectionGate gate({8.0, 500, 3});
  gate.Add(Pose2D{0.02, 0.0, 0.005}, 0.8);
  gate.Add(Pose2D{0.02, 0.0, 0.005}, 0.8);
  EXPECT_FALSE(gate.Bound(0).has_value());
  EXPECT_FALSE(gate.Refuses(Pose2D{}, Pose2D{5.0, 0.0, 1.0}, RefinementSupport{0.1, {}}, 0));
  gate.Add(Pose2D{0.02, 0.0, 0.005}, 0.8);
  ASSERT_TRUE(gate.Bound(0).has_value());
}

TEST(CorrectionGate, TheBoundIsFactorTimesTheMedianCorrectionGrowingWithTheUnconfirmedScans) {
  const CorrectionGate gate = Learned();
  const CorrectionBound now = *gate.Bound(0);
  EXPECT_NEAR(now.translation_m, 8.0 * 0.02, 1e-12);
  EXPECT_NEAR(now.rotation_rad, 8.0 * 0.005, 1e-12);
  const CorrectionBound after_three = *gate.Bound(3);  // √4 = 2 times wider
  EXPECT_NEAR(after_three.translation_m, 2.0 * now.translation_m, 1e-12);
  EXPECT_NEAR(after_three.rotation_rad, 2.0 * now.rotation_rad, 1e-12);
}

TEST(CorrectionGate, ALargeCorrectionOnLittleOverlapIsRefusedAndOnUsualOverlapKept) {
  const Pose2D prediction{3.0, -2.0, 0.5};
  const Pose2D turned = prediction * Pose2D{0.0, 0.0, 0.14};  // 0.14 rad > 8 · 0.005
  CorrectionGate gate = Learned();
  EXPECT_TRUE(
      gate.Refuses(prediction, turned, RefinementSupport{0.35, {}}, 0));  // 0.35 < 0.75 · 0.8
  gate = Learned();
  EXPECT_FALSE(
      gate.Refuses(prediction, turned, RefinementSupport{0.7, {}}, 0));  // as much overlap as usual
  gate = Learned();
  const Pose2D small = prediction * Pose2D{0.1, 0.0, 0.03};  // within 0.16 m and 0.04 rad
  EXPECT_FALSE(gate.Refuses(prediction, small, RefinementSupport{0.35, {}}, 0));
}

TEST(CorrectionGate, LowOverlapIsBelowTheOverlapFractionOfTheMedianMatchRatioOnceLearned) {
  CorrectionGateOptions options;
  options.min_samples = 10;
  CorrectionGate gate(options);
  for (int i = 0; i < 9; ++i) gate.Add(Pose2D{0.02, 0.0, 0.005}, 0.8);
  EXPECT_FALSE(gate.LowOverlap(0.1));  // nine confirmed scans: nothing learned yet
  gate.Add(Pose2D{0.02, 0.0, 0.005}, 0.8);
  // 0.75 × 0.8 = 0.6
  EXPECT_TRUE(gate.LowOverlap(0.59));
  EXPECT_FALSE(gate.LowOverlap(0.61));
}

TEST(CorrectionGate, TheWeakAxisRatioIsTheDeviationAlongADirectionOverTheSmallest) {
  // A corridor along x: 0.04 m of deviation along it, 0.01 m across.
  const Eigen::Matrix2d corridor = Eigen::Vector2d(0.04 * 0.04, 0.01 * 0.01).asDiagonal();
  EXPECT_NEAR(WeakAxisRatio(corridor, Eigen::Vector2d(1.0, 0.0)), 4.0, 1e-12);
  EXPECT_NEAR(WeakAxisRatio(corridor, Eigen::Vector2d(0.0, -2.0)), 1.0, 1e-12);
  EXPECT_NEAR(WeakAxisRatio(corridor, Eigen::Vector2d(1.0, 1.0)), std::sqrt(8.5), 1e-12);
  EXPECT_EQ(WeakAxisRatio(corridor, Eigen::Vector2d::Zero()), 0.0);
}

TEST(CorrectionGate, ASlideAlongTheLeastConstrainedAxisIsRefusedOnFullOverlap) {
  const Eigen::Matrix2d corridor = Eigen::Vector2d(0.04 * 0.04, 0.01 * 0.01).asDiagonal();
  const Pose2D prediction{1.0, 1.0, 0.0};
  CorrectionGate gate = Learned();
  // 0.5 m along the corridor (> 8 · 0.02 m), with as much overlap as usual.
  EXPECT_TRUE(gate.Refuses(prediction, Pose2D{1.5, 1.0, 0.0}, RefinementSupport{0.8, corridor}, 0));
  gate = Learned();
  // The same across it: the scan constrains that direction best, the correction stands.
  EXPECT_FALSE(
      gate.Refuses(prediction, Pose2D{1.0, 1.5, 0.0}, RefinementSupport{0.8, corridor}, 0));
  gate = Learned();
  // Without a covariance nothing says the direction is weak.
  EXPECT_FALSE(gate.Refuses(prediction, Pose2D{1.5, 1.0, 0.0}, RefinementSupport{0.8, {}}, 0));
}

// A refinement still moving when its iterations ran out states a covariance taken where it
// stopped: round here, though it slid 0.5 m (acapulco's corridor, 0.59 m in 15 iterations).
TEST(CorrectionGate, ASlideByARefinementThatDidNotConvergeIsRefusedWhateverItsCovariance) {
  const Eigen::Matrix2d round = Eigen::Vector2d(0.01 * 0.01, 0.01 * 0.01).asDiagonal();
  const Pose2D prediction{1.0, 1.0, 0.0};
  CorrectionGate gate = Learned();
  EXPECT_TRUE(
      gate.Refuses(prediction, Pose2D{1.5, 1.0, 0.0}, RefinementSupport{0.8, round, false}, 0));
  gate = Learned();
  // Converged, with a round covariance: the scan demands the correction.
  EXPECT_FALSE(
      gate.Refuses(prediction, Pose2D{1.5, 1.0, 0.0}, RefinementSupport{0.8, round, true}, 0));
  gate = Learned();
  // Beyond the bound in heading too: a turn where the odometry slipped, not a slide.
  EXPECT_FALSE(
      gate.Refuses(prediction, Pose2D{1.5, 1.0, 0.5}, RefinementSupport{0.8, round, false}, 0));
  gate = Learned();
  // Within the bound (8 · 0.02 m): nothing to judge.
  EXPECT_FALSE(
      gate.Refuses(prediction, Pose2D{1.1, 1.0, 0.0}, RefinementSupport{0.8, round, false}, 0));
}

// Within a stretch the rules reject, a refinement they rejected supports no correction beyond the
// bound: not a turn (ACES seen over 120°: 55° and 6.4 m, 150 scans into such a stretch), not a
// converged fit on a round covariance. The first scan rejected after confirmed ones keeps the
// exemptions: a slip of the odometry may be what failed it (Fr079 kept a scan a metre, scan 113).
TEST(CorrectionGate, AnUnvalidatedCorrectionBeyondTheBoundIsRefusedWithinAnUnconfirmedStretch) {
  const Eigen::Matrix2d round = Eigen::Vector2d(0.01 * 0.01, 0.01 * 0.01).asDiagonal();
  const Pose2D prediction{1.0, 1.0, 0.0};
  const Pose2D turned{1.5, 1.0, 0.5}, moved{1.5, 1.0, 0.0}, near{1.1, 1.0, 0.03};
  const RefinementSupport rejected{0.8, round, true, false}, validated{0.8, round, true, true};
  for (const Pose2D& refined : {turned, moved}) {
    CorrectionGate gate = Learned();
    EXPECT_TRUE(gate.Refuses(prediction, refined, rejected, 1));
    gate = Learned();  // the first unconfirmed scan: the turn and the converged fit stand
    EXPECT_FALSE(gate.Refuses(prediction, refined, rejected, 0));
    gate = Learned();  // validated: they stand
    EXPECT_FALSE(gate.Refuses(prediction, refined, validated, 1));
  }
  // Within the bound (√2 · 0.16 m, √2 · 0.04 rad) a rejected refinement is not the gate's to judge.
  CorrectionGate gate = Learned();
  EXPECT_FALSE(gate.Refuses(prediction, near, rejected, 1));
  // The next scan lands on the refused turn: rejected by the rules too, it is no evidence of a
  // slipping odometry (ACES over 120°, scans 3724–3725: both from the candidates turned 10°);
  // validated, it is.
  const Pose2D step{0.5, 0.0, 0.0};
  for (const bool valid : {false, true}) {
    gate = Learned();
    ASSERT_TRUE(gate.Refuses(prediction, turned, rejected, 1));
    gate.Moved(step);
    EXPECT_EQ(gate.Refuses(prediction * step, turned * step, valid ? validated : rejected, 2),
              !valid);
  }
  CorrectionGateOptions off;
  off.refuse_unvalidated = false;
  gate = Learned(off);
  EXPECT_FALSE(gate.Refuses(prediction, turned, rejected, 1));
}

// Eight scans into a stretch the rules reject the bound has widened threefold, for an odometry
// whose error grew over the stretch; a refinement the rules rejected is held to the bound of one
// step (ACES with a laser 1 cm noisier, scans 2785-2786: 9.7° and 12.4° from the prediction on
// unconfirmed scans, within the widened 21°, and the session lost its map).
TEST(CorrectionGate, WithUnvalidatedOneStepAnUnvalidatedCorrectionIsHeldToTheBoundOfOneStep) {
  CorrectionGateOptions one_step;
  one_step.unvalidated_one_step = true;
  const Eigen::Matrix2d round = Eigen::Vector2d(0.01 * 0.01, 0.01 * 0.01).asDiagonal();
  const Pose2D prediction{1.0, 1.0, 0.0};
  const Pose2D turned{1.0, 1.0, 0.08}, moved{1.3, 1.0, 0.0};  // beyond 0.16 m / 0.04 rad
  const RefinementSupport rejected{0.8, round, true, false}, validated{0.8, round, true, true};
  for (const Pose2D& refined : {turned, moved}) {
    CorrectionGate gate = Learned(one_step);
    ASSERT_FALSE(gate.Bound(8)->Exceeded(Between(prediction, refined)));  // within the widened
    EXPECT_TRUE(gate.Refuses(prediction, refined, rejected, 8));
    gate = Learned(one_step);
    EXPECT_FALSE(gate.Refuses(prediction, refined, validated, 8));
    gate = Learned(
        one_step);  // the first unconfirmed scan: a slip of the odometry may be what failed it
    EXPECT_FALSE(gate.Refuses(prediction, refined, rejected, 0));
    gate = Learned();  // the default: the widened bound
    EXPECT_FALSE(gate.Refuses(prediction, refined, rejected, 8));
  }
}

// Before the slide check has learned, no correction is large: a slide is told by the
// refinement alone (orebro, a laser 1 cm noisier: scan 11 slid 0.35 m along a weak axis in 15
// outer iterations, 8 scans into the session).
TEST(CorrectionGate, ASlideIsARefinementStillMovingAlongItsWeakestAxisWhateverItsSize) {
  const Eigen::Matrix2d corridor = Eigen::Vector2d(0.04 * 0.04, 0.01 * 0.01).asDiagonal();
  const Pose2D prediction{1.0, 1.0, 0.0};
  const CorrectionGate gate;  // nothing learned
  // 2 cm along the corridor, not converged: a slide, however small.
  EXPECT_TRUE(
      gate.Slides(prediction, Pose2D{1.02, 1.0, 0.0}, RefinementSupport{0.8, corridor, false}));
  // Converged there: the refinement stopped where the scan put it.
  EXPECT_FALSE(
      gate.Slides(prediction, Pose2D{1.02, 1.0, 0.0}, RefinementSupport{0.8, corridor, true}));
  // Across the corridor (the best-constrained direction), or along a direction 2.9 times weaker
  // than the best (< 3): not along the weak axis.
  EXPECT_FALSE(
      gate.Slides(prediction, Pose2D{1.0, 1.5, 0.0}, RefinementSupport{0.8, corridor, false}));
  const Eigen::Matrix2d nearly = Eigen::Vector2d(0.029 * 0.029, 0.01 * 0.01).asDiagonal();
  EXPECT_FALSE(
      gate.Slides(prediction, Pose2D{1.5, 1.0, 0.0}, RefinementSupport{0.8, nearly, false}));
  // No covariance, nothing says the direction is weak.
  EXPECT_FALSE(gate.Slides(prediction, Pose2D{1.5, 1.0, 0.0}, RefinementSupport{0.8, {}, false}));
}

TEST(CorrectionGate, ARefusedPostureTheNextScanAgreesWithIsKept) {
  CorrectionGate gate = Learned();
  const Pose2D prediction{0.0, 0.0, 0.0};
  const Pose2D refined{0.0, 0.3, 0.1};
  ASSERT_TRUE(gate.Refuses(prediction, refined, RefinementSupport{0.35, {}}, 0));
  const Pose2D step{0.5, 0.0, 0.05};
  gate.Moved(step);
  // The next scan's refinement lands on the refused posture carried by the step, 1 cm off:
  // within 3 · the median corrections, so the odometry slipped and the correction stands.
  const Pose2D agreeing = refined * step * Pose2D{0.01, 0.0, 0.0};
  EXPECT_FALSE(gate.Refuses(prediction * step, agreeing, RefinementSupport{0.35, {}}, 1));
}

TEST(CorrectionGate, ARefusedPostureTheNextScanContradictsIsRefusedAgain) {
  CorrectionGate gate = Learned();
  const Pose2D prediction{0.0, 0.0, 0.0};
  ASSERT_TRUE(gate.Refuses(prediction, Pose2D{0.0, 0.3, 0.1}, RefinementSupport{0.35, {}}, 0));
  const Pose2D step{0.5, 0.0, 0.0};
  gate.Moved(step);
  // Turned the other way beyond the bound after one unconfirmed scan (√2 · 0.04 rad).
  EXPECT_TRUE(gate.Refuses(prediction * step, prediction * step * Pose2D{0.0, -0.3, -0.1},
                           RefinementSupport{0.35, {}}, 1));
}

TEST(CorrectionGate, AFactorOfZeroTurnsTheGateOff) {
  CorrectionGateOptions options;
  options.factor = 0.0;
  CorrectionGate gate = Learned(options);
  EXPECT_FALSE(gate.Bound(0).has_value());
  EXPECT_FALSE(gate.Refuses(Pose2D{}, Pose2D{5.0, 0.0, 1.0}, RefinementSupport{0.1, {}}, 0));
}

TEST(CorrectionGate, OptionsOutOfTheirDomainAreRefused) {
  CorrectionGateOptions options;
  options.factor = -1.0;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options = {};
  options.min_samples = 0;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options = {};
  options.overlap_fraction = 1.5;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options = {};
  options.weak_axis_ratio = 0.5;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
