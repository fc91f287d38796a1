#include "scanloc/session/odometry_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace scanloc {
namespace {

// Steps of a sparse log (0.5–1 m, turns up to ±0.5 rad), the odometry reporting each
// `distance_error` times as long and `turn_error` times as sharp as the robot drove, the matcher
// erring by 1 cm and 3 mrad (σ, fixed seed). Every `outlier_every`-th match (0: none) is 0.5 m and
// 0.2 rad off, as a wrong match.
void Teach(OdometryCalibration& calibration, int steps, double distance_error, double turn_error,
           int outlier_every = 0, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> length(0.5, 1.0), turn(-0.5, 0.5);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int i = 1; i <= steps; ++i) {
    const double d = length(rng), yaw = turn(rng);
    const Pose2D driven{d * std::cos(0.5 * yaw), d * std::sin(0.5 * yaw), yaw};
    const Pose2D reported{distance_error * driven.x_m, distance_error * driven.y_m,
                          turn_error * driven.yaw_rad};
    Pose2D matched{driven.x_m + 0.01 * noise(rng), driven.y_m + 0.01 * noise(rng),
                   driven.yaw_rad + 0.003 * noise(rng)};
    if (outlier_every > 0 && i % outlier_every == 0) {
      matched.x_m += 0.5;
      matched.yaw_rad += 0.2;
    }
    calibration.Learn(reported, matched);
  }
}

OdometryCalibrationOptions Applied() {
  OdometryCalibrationOptions options;
  options.apply = true;
  return options;
}

TEST(OdometryCalibration, RecoversTheScalesOfAnOdometryFivePerCentLongAndThreePerCentSharp) {
  OdometryCalibration calibration(Applied());
  Teach(calibration, 300, 1.05, 1.03);
  EXPECT_TRUE(calibration.distance().significant);
  EXPECT_TRUE(calibration.turn().significant);
  EXPECT_NEAR(calibration.distance().value, 1.0 / 1.05, 0.005);
  EXPECT_NEAR(calibration.turn().value, 1.0 / 1.03, 0.003);
  EXPECT_LT(calibration.distance().standard_error, 0.005);
  // A step as reported comes back as driven.
  const Pose2D calibrated = calibration.Calibrated({1.05, 0.105, 0.103});
  EXPECT_NEAR(calibrated.x_m, 1.0, 0.005);
  EXPECT_NEAR(calibrated.y_m, 0.1, 0.001);
  EXPECT_NEAR(calibrated.yaw_rad, 0.1, 0.0005);
}

TEST(OdometryCalibration, WrongMatchesOneInTenDoNotMoveTheScales) {
  OdometryCalibration calibration(Applied());
  Teach(calibration, 300, 1.05, 1.03, 10);
  EXPECT_NEAR(calibration.distance().value, 1.0 / 1.05, 0.008);
  EXPECT_NEAR(calibration.turn().value, 1.0 / 1.03, 0.005);
}

TEST(OdometryCalibration, AWellCalibratedOdometryIsPassedOnAsGiven) {
  OdometryCalibration calibration(Applied());
  Teach(calibration, 300, 1.0, 1.0);
  EXPECT_FALSE(calibration.distance().significant);
  EXPECT_FALSE(calibration.turn().significant);
  EXPECT_NEAR(calibration.distance().fitted, 1.0, 0.005);
  const Pose2D step{0.7, -0.1, 0.3};
  const Pose2D calibrated = calibration.Calibrated(step);
  EXPECT_EQ(calibrated.x_m, step.x_m);
  EXPECT_EQ(calibrated.y_m, step.y_m);
  EXPECT_EQ(calibrated.yaw_rad, step.yaw_rad);
}

TEST(OdometryCalibration, AnErrorWithinMinChangeIsNotSignificant) {
  // 0.6 % is measured (the fit is good to about 0.1 %) but stays below the 1 % that counts.
  OdometryCalibration calibration(Applied());
  Teach(calibration, 600, 1.006, 1.0);
  EXPECT_NEAR(calibration.distance().fitted, 1.0 / 1.006, 0.003);
  EXPECT_FALSE(calibration.distance().significant);
  EXPECT_EQ(calibration.distance().value, 1.0);
}

TEST(OdometryCalibration, NothingIsAppliedBeforeMinSamplesSteps) {
  OdometryCalibration calibration(Applied());
  Teach(calibration, 29, 1.2, 1.2);
  EXPECT_FALSE(calibration.distance().significant);
  EXPECT_EQ(calibration.Calibrated({1.0, 0.0, 0.5}).x_m, 1.0);
  Teach(calibration, 1, 1.2, 1.2, 0, 8);  // the 30th: fitted at once (refit_every 10 divides it)
  EXPECT_TRUE(calibration.distance().significant);
}

TEST(OdometryCalibration, StepsShorterThanTheMinimaAreLeftForTheCallerToExtend) {
  OdometryCalibration calibration(Applied());
  EXPECT_FALSE(calibration.Learn({0.0, 0.0, 0.0}, {0.01, 0.0, 0.001}));
  EXPECT_FALSE(calibration.Learn({0.05, 0.0, 0.02}, {0.048, 0.0, 0.019}));  // a Kümmerle step
  EXPECT_EQ(calibration.samples(), 0u);
  EXPECT_TRUE(calibration.Learn({0.6, 0.0, 0.0}, {0.58, 0.0, 0.0}));  // far enough
  EXPECT_TRUE(calibration.Learn({0.0, 0.0, 0.3}, {0.0, 0.0, 0.29}));  // or turned enough
  EXPECT_EQ(calibration.samples(), 2u);
  // A turn on the spot teaches the turn only.
  for (int i = 0; i < 40; ++i) calibration.Learn({0.0, 0.0, 0.3}, {0.0, 0.0, 0.3 / 1.05});
  EXPECT_EQ(calibration.distance().samples, 1u);
  EXPECT_FALSE(calibration.distance().significant);
  EXPECT_TRUE(calibration.turn().significant);
}

TEST(OdometryCalibration, TheWindowForgetsTheOldestSteps) {
  OdometryCalibrationOptions options = Applied();
  options.window = 200;
  OdometryCalibration calibration(options);
  Teach(calibration, 300, 1.1, 1.0);  // a wheel changed ...
  Teach(calibration, 200, 1.0, 1.0);  // ... and changed back: only these are remembered
  EXPECT_EQ(calibration.samples(), 200u);
  EXPECT_NEAR(calibration.distance().fitted, 1.0, 0.005);
  EXPECT_FALSE(calibration.distance().significant);
}

TEST(OdometryCalibration, UnlessAppliedTheScalesAreReportedAndTheOdometryPassedOnAsGiven) {
  OdometryCalibration calibration;  // the default: learned and reported only
  Teach(calibration, 300, 1.05, 1.03);
  EXPECT_TRUE(calibration.distance().significant);
  EXPECT_NEAR(calibration.distance().fitted, 1.0 / 1.05, 0.005);
  EXPECT_EQ(calibration.distance().value, 1.0);
  EXPECT_EQ(calibration.turn().value, 1.0);
  EXPECT_FALSE(calibration.applies());
  EXPECT_EQ(calibration.Calibrated({1.05, 0.1, 0.3}).x_m, 1.05);
}

TEST(OdometryCalibration, DisabledItLearnsNothing) {
  OdometryCalibrationOptions options = Applied();
  options.enabled = false;
  OdometryCalibration calibration(options);
  Teach(calibration, 100, 1.2, 1.2);
  EXPECT_EQ(calibration.samples(), 0u);
  EXPECT_EQ(calibration.Calibrated({1.0, 0.0, 0.5}).x_m, 1.0);
}

TEST(OdometryCalibrationOptions, AbsurdValuesAreRefused) {
  OdometryCalibrationOptions options;
  options.min_samples = 0;
  EXPECT_THROW(OdometryCalibration{options}, std::invalid_argument);
  options = {};
  options.max_scale = 1.0;
  EXPECT_THROW(OdometryCalibration{options}, std::invalid_argument);
  options = {};
  options.min_change = -0.1;
  EXPECT_THROW(OdometryCalibration{options}, std::invalid_argument);
  options = {};
  options.significance = std::nan("");
  EXPECT_THROW(OdometryCalibration{options}, std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
