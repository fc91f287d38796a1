#include "scanloc/session/correction_drift.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace scanloc {
namespace {

// A robot driving along x in 0.3 m steps, scans from..to-1; each confirmed scan corrected by
// `correction` (none: not confirmed). A 5 m window holds 17 scans (4.8 m of path).
void Drive(CorrectionDrift& drift, int from, int to,
           const std::optional<Eigen::Vector2d>& correction, bool held = false) {
  for (int i = from; i < to; ++i) {
    const Pose2D prediction(0.3 * i, 0.0, 0.0);
    drift.Predicted(prediction);
    drift.Kept(prediction, correction, held);
  }
}

// An odometry that the scans correct by 2 mm along x at every step: a full window sums to
// 17 · 0.002 = 0.034 m, the median sum of 100 scans is that, and the bound 8 · 0.034 = 0.272 m.
CorrectionDrift Learned(CorrectionDriftOptions o = {}) {
  CorrectionDrift drift(o);
  Drive(drift, 0, 100, Eigen::Vector2d(0.002, 0.0));
  return drift;
}

TEST(CorrectionDrift, LearnsItsBoundAsTheFactorTimesTheMedianSum) {
  const CorrectionDrift drift = Learned();
  EXPECT_NEAR(drift.Sum(), 0.034, 1e-12);
  ASSERT_TRUE(drift.Bound().has_value());
  EXPECT_NEAR(*drift.Bound(), 0.272, 1e-12);
}

TEST(CorrectionDrift, RefusesACorrectionThatTakesTheSumBeyondTheBoundAndFarther) {
  CorrectionDrift drift = Learned();
  EXPECT_FALSE(drift.Refuses({0.2, 0.0}));   // 0.234 m
  EXPECT_TRUE(drift.Refuses({0.25, 0.0}));   // 0.284 m
  EXPECT_FALSE(drift.Refuses({-0.3, 0.0}));  // 0.266 m the other way
  // A slide across: corrections of 0.1 m along -y, confirmed while the sum stays within; the
  // window then holds 15 of the 2 mm corrections.
  Drive(drift, 100, 102, Eigen::Vector2d(0.0, -0.1));
  EXPECT_NEAR(drift.Sum(), std::hypot(0.030, 0.2), 1e-12);
  EXPECT_TRUE(drift.Refuses({0.0, -0.1}));    // 0.302 m, and farther than 0.202 m
  EXPECT_FALSE(drift.Refuses({0.0, 0.1}));    // back towards zero
  EXPECT_FALSE(drift.Refuses({0.0, -0.05}));  // 0.253 m
}

TEST(CorrectionDrift, NeverRefusesBelowTheFloorItIsGiven) {
  // Corrections that vanish: the median sum, and the learned bound, are 0.
  CorrectionDrift drift;
  Drive(drift, 0, 100, Eigen::Vector2d(0.0, 0.0));
  ASSERT_TRUE(drift.Bound().has_value());
  EXPECT_DOUBLE_EQ(*drift.Bound(), 0.0);
  EXPECT_TRUE(drift.Refuses({0.01, 0.0}));
  EXPECT_FALSE(drift.Refuses({0.01, 0.0}, 0.05));
  EXPECT_TRUE(drift.Refuses({0.06, 0.0}, 0.05));
}

TEST(CorrectionDrift, IsOpenUntilItHasLearnedMinSamplesSums) {
  CorrectionDrift drift;
  Drive(drift, 0, 19, Eigen::Vector2d(0.002, 0.0));
  EXPECT_FALSE(drift.Bound().has_value());
  EXPECT_FALSE(drift.Refuses({-5.0, 0.0}));
  Drive(drift, 19, 20, Eigen::Vector2d(0.002, 0.0));
  EXPECT_TRUE(drift.Bound().has_value());
  EXPECT_TRUE(drift.Refuses({-5.0, 0.0}));
}

TEST(CorrectionDrift, AnOdometryThatErrsAlikeAtEveryStepRaisesItsOwnBound) {
  // Every scan corrected by 0.03 m backwards: 17 · 0.03 = 0.51 m over a window.
  CorrectionDrift drift;
  Drive(drift, 0, 200, Eigen::Vector2d(-0.03, 0.0));
  ASSERT_TRUE(drift.Bound().has_value());
  EXPECT_NEAR(*drift.Bound(), 8.0 * 0.51, 1e-9);
  EXPECT_FALSE(drift.Refuses({-0.03, 0.0}));
}

TEST(CorrectionDrift, ForgetsCorrectionsOlderThanTheWindowOfPath) {
  CorrectionDrift drift = Learned();
  Drive(drift, 100, 102, Eigen::Vector2d(0.0, -0.12));  // 0.24 m across
  EXPECT_TRUE(drift.Refuses({0.0, -0.1}));
  // 6 m further without a confirmed correction: the window is empty again.
  Drive(drift, 102, 122, std::nullopt);
  EXPECT_DOUBLE_EQ(drift.Sum(), 0.0);
  EXPECT_FALSE(drift.Refuses({0.0, -0.1}));
}

TEST(CorrectionDrift, AHeldScanNeitherMovesTheWindowOnNorTeachesItsSum) {
  CorrectionDrift drift = Learned();
  Drive(drift, 100, 102, Eigen::Vector2d(0.0, -0.12));  // 0.24 m across
  ASSERT_TRUE(drift.Refuses({0.0, -0.1}));
  // Held over 6 m: the sum is not forgotten, and no sum is learned; the bound widens to
  // 0.272 · √(1 + 6 / 5) = 0.403 m.
  const double sum = drift.Sum();
  Drive(drift, 102, 122, Eigen::Vector2d(0.0, 0.0), true);
  EXPECT_DOUBLE_EQ(drift.Sum(), sum);
  EXPECT_NEAR(*drift.Bound(), 0.272 * std::sqrt(2.2), 1e-9);
  EXPECT_TRUE(drift.Refuses({0.0, -0.2}));   // 0.441 m
  EXPECT_FALSE(drift.Refuses({0.0, -0.1}));  // 0.342 m
}

TEST(CorrectionDrift, TheBoundWidensWithThePathDrivenWhileHeldLikeARandomWalk) {
  CorrectionDrift drift = Learned();
  Drive(drift, 100, 150, std::nullopt, true);  // 15 m held: √(1 + 15 / 5) = 2
  ASSERT_TRUE(drift.Bound().has_value());
  EXPECT_NEAR(*drift.Bound(), 2.0 * 0.272, 1e-9);
  // A confirmed correction within the learned bound again: the widening is over.
  Drive(drift, 150, 151, Eigen::Vector2d(0.002, 0.0));
  EXPECT_NEAR(*drift.Bound(), 0.272, 1e-9);
}

TEST(CorrectionDrift, AClosureThatMovesThePostureIsNoPathDriven) {
  // The last posture kept is x = 29.7 m; a closure's solve moves the session 100 m on, and the
  // next scan is predicted one 0.3 m step from there: the window loses its oldest correction
  // only (16 · 0.002 = 0.032 m), not all of them as a 100.3 m step would.
  CorrectionDrift drift = Learned();
  drift.Moved(Pose2D(129.7, 0.0, 0.0));
  drift.Predicted(Pose2D(130.0, 0.0, 0.0));
  const std::optional<SlideCheck> check = drift.Check({0.0, 0.0});
  ASSERT_TRUE(check.has_value());
  EXPECT_NEAR(check->before_m, 0.032, 1e-12);
}

TEST(CorrectionDrift, AZeroWindowTurnsTheCheckOff) {
  CorrectionDriftOptions off;
  off.window_m = 0.0;
  const CorrectionDrift drift = Learned(off);
  EXPECT_FALSE(drift.Bound().has_value());
  EXPECT_FALSE(drift.Refuses({-5.0, 0.0}));
  EXPECT_DOUBLE_EQ(drift.Sum(), 0.0);
}

TEST(CorrectionDrift, RefusesOptionsOutOfTheirDomain) {
  CorrectionDriftOptions o;
  o.window_m = -1.0;
  EXPECT_THROW(CorrectionDrift{o}, std::invalid_argument);
  o = {};
  o.factor = 0.0;
  EXPECT_THROW(CorrectionDrift{o}, std::invalid_argument);
  o = {};
  o.min_samples = o.samples + 1;
  EXPECT_THROW(CorrectionDrift{o}, std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
