// The odometry model learned from closures and stretches of a synthetic drive: a perfect odometry
// is found far more precise than the matched chain, a drifting one as noisy as it is, and the
// matched chain's scale as understated as it was made.

#include "scanloc/graph/odometry_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "scanloc/graph/relative_covariance.hpp"

namespace scanloc {
namespace {

// The graph-unit covariance of every matched step: the real one is 9 times larger.
const Eigen::Matrix3d kMatchedCovariance = Eigen::Vector3d(2.5e-5, 2.5e-5, 1e-6).asDiagonal();
constexpr double kMatchedScale = 9.0;

struct Drive {
  std::vector<Pose2D> truth_steps, matched_steps, odometry_steps;
};

// 600 steps of 0.9 m turning by up to ±0.3 rad (seed 9; the jitter's 11). The matched steps err by
// the matched covariance times its scale, and each matched posture besides by `jitter_m` (σ, on x
// and y) and `jitter_rad` that the next step undoes, as a scan matched on a map does; the
// odometry's heading by `heading_rad2_per_m` per metre and its position by `position_m2_per_m`.
Drive MakeDrive(double heading_rad2_per_m, double position_m2_per_m, double jitter_m = 0.0,
                double jitter_rad = 0.0) {
  std::mt19937 random(9);
  std::uniform_real_distribution<double> turn(-0.3, 0.3);
  std::normal_distribution<double> unit(0.0, 1.0);
  Drive drive;
  const Eigen::Vector3d matched_sigma = (kMatchedScale * kMatchedCovariance.diagonal()).cwiseSqrt();
  std::mt19937 jitter_random(11);
  Pose2D jitter;  // of the step's start
  for (int k = 0; k < 600; ++k) {
    const Pose2D step(0.9, 0.0, turn(random));
    drive.truth_steps.push_back(step);
    Pose2D next_jitter(jitter_m * unit(jitter_random), jitter_m * unit(jitter_random), 0.0);
    if (jitter_rad > 0.0) next_jitter.yaw_rad = jitter_rad * unit(jitter_random);
    const Pose2D jittered = jitter.Inverse() * step * next_jitter;
    jitter = next_jitter;
    drive.matched_steps.push_back(Pose2D(jittered.x_m + matched_sigma(0) * unit(random),
                                         jittered.y_m + matched_sigma(1) * unit(random),
                                         jittered.yaw_rad + matched_sigma(2) * unit(random)));
    const double p = std::sqrt(position_m2_per_m * 0.9);
    const double h = std::sqrt(heading_rad2_per_m * (0.9 + std::abs(step.yaw_rad)));
    drive.odometry_steps.push_back(Pose2D(step.x_m + p * unit(random), step.y_m + p * unit(random),
                                          step.yaw_rad + h * unit(random)));
  }
  return drive;
}

// The misses of steps [a, b) against the truth's relative posture plus `closure_noise` (a closure,
// its own covariance stated from `closure_noise_sigma`) or, without it, of the odometry chain
// against the matched one (a stretch).
ChainMisses Misses(const Drive& drive, const OdometryModel& model, int a, int b,
                   const std::optional<Eigen::Vector3d>& closure_noise,
                   const Eigen::Vector3d& closure_noise_sigma = Eigen::Vector3d::Zero()) {
  CompoundedPosture truth, matched, position, heading, floor;
  for (int k = a; k < b; ++k) {
    truth.Append(drive.truth_steps[k], Eigen::Matrix3d::Zero());
    matched.Append(drive.matched_steps[k], kMatchedCovariance);
    const OdometryStepShape shape = model.Shape(drive.odometry_steps[k]);
    position.Append(drive.odometry_steps[k], shape.position);
    heading.Append(drive.odometry_steps[k], shape.heading);
    floor.Append(drive.odometry_steps[k], shape.floor);
  }
  auto miss = [](const Pose2D& measured, const Pose2D& chain) {
    return Eigen::Vector3d(measured.x_m - chain.x_m, measured.y_m - chain.y_m,
                           NormalizeAngle(measured.yaw_rad - chain.yaw_rad));
  };
  Pose2D measured = matched.T_start_end;
  if (closure_noise)
    measured =
        truth.T_start_end * Pose2D((*closure_noise)(0), (*closure_noise)(1), (*closure_noise)(2));
  ChainMisses m;
  m.path_m = 0.9 * (b - a);
  m.matched_miss = closure_noise ? miss(measured, matched.T_start_end) : Eigen::Vector3d::Zero();
  m.odometry_miss = miss(measured, position.T_start_end);
  m.matched_covariance = matched.covariance;
  m.odometry_per_position = position.covariance;
  m.odometry_per_heading = heading.covariance;
  m.odometry_floor = floor.covariance;
  m.translation_m = measured.Translation();
  // A closure's own covariance as its refinement states it: understated as a matched step's.
  if (closure_noise)
    m.closure_covariance = closure_noise_sigma.cwiseAbs2().asDiagonal() * (1.0 / kMatchedScale);
  return m;
}

// Closures of 20–60 steps every `every` steps from step 60 (2 cm and `closure_rad` of their own
// error, seed 4), stretches of 3, 6, 12 and 24 steps (2.7–21.6 m) along the whole drive, as a
// session cuts them.
OdometryModel Learned(const Drive& drive, const OdometryModelOptions& options = {},
                      double closure_rad = 0.005, int every = 30) {
  OdometryModel model{options};
  std::mt19937 random(4);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<ChainMisses> closures, stretches;
  for (int b = 60; b <= 600; b += every) {
    const int a = b - 20 - (b / 30 % 3) * 20;
    closures.push_back(Misses(
        drive, model, a, b,
        Eigen::Vector3d(0.02 * unit(random), 0.02 * unit(random), closure_rad * unit(random)),
        Eigen::Vector3d(0.02, 0.02, closure_rad)));
  }
  for (int length = 3; length <= 24; length *= 2)
    for (int a = 0; a + length <= 600; a += length)
      stretches.push_back(Misses(drive, model, a, a + length, {}));
  model.Learn(closures, stretches);
  return model;
}

TEST(OdometryModel, APerfectOdometryIsLearnedTenTimesMorePreciseInHeadingThanAMatchedStep) {
  const OdometryModel model = Learned(MakeDrive(0.0, 0.0));
  ASSERT_TRUE(model.learned());
  EXPECT_EQ(model.closures(), 19u);
  EXPECT_LT(model.heading_rad2_per_m(), 1e-6);
  EXPECT_NEAR(model.matched_scale(), kMatchedScale, 0.5 * kMatchedScale);
  // In the graph's units, beside the matched step's 1e-6 rad².
  EXPECT_LT(model.StepCovariance(Pose2D(0.9, 0.0, 0.2))(2, 2), 0.1 * kMatchedCovariance(2, 2));
}

TEST(OdometryModel, ADriftingOdometryIsLearnedAsNoisyAsItIsWithinHalf) {
  const double heading = 1e-4, position = 4e-4;
  const OdometryModel model = Learned(MakeDrive(heading, position));
  EXPECT_NEAR(model.heading_rad2_per_m(), heading, 0.5 * heading);
  EXPECT_NEAR(model.position_m2_per_m(), position, 0.5 * position);
  EXPECT_NEAR(model.matched_scale(), kMatchedScale, 0.5 * kMatchedScale);
  // Weaker than a matched step in heading: the graph follows the matching there.
  EXPECT_GT(model.StepCovariance(Pose2D(0.9, 0.0, 0.2))(2, 2), kMatchedCovariance(2, 2));
}

// The matching's jitter (3 cm at each matched posture) does not grow with a stretch's length, the
// odometry's noise would: a perfect odometry's position is not taken for as noisy as the jitter
// (2 × 9e-4 m² over a 10.8 m stretch would pass for 1.7e-4 m² per metre).
TEST(OdometryModel, APerfectOdometrysPositionIsNotTakenForTheMatchingsJitter) {
  const OdometryModel model = Learned(MakeDrive(0.0, 0.0, 0.03));
  EXPECT_LT(model.position_m2_per_m(), 1e-5);
  EXPECT_LT(model.heading_rad2_per_m(), 1e-6);
}

// Closures erring by 20 mrad of their own in heading (the Radish closures err by 1–36 mrad), as a
// scan matched on a map errs: the matched postures jitter by 14 mrad that the next step undoes.
// Zero heading noise and a little of it explain the misses alike, and the fit alone settles on a
// little; the paired test (paired_misses.hpp) finds the closures' error in both chains' misses and
// leaves the odometry as it came: perfect, in heading and in position. It finds the jitter too.
TEST(OdometryModel, APerfectOdometryIsNotTakenForNoisyByClosuresThatErrAsTheMatchingJitters) {
  const Drive drive = MakeDrive(0.0, 0.0, 0.0, 0.014);
  OdometryModelOptions untested;
  untested.heading_test_chi2 = 0.0;
  untested.position_test_chi2 = 0.0;
  const OdometryModel fitted = Learned(drive, untested, 0.02);
  EXPECT_GT(fitted.heading_rad2_per_m(), 1e-7);
  const OdometryModel tested = Learned(drive, {}, 0.02);
  EXPECT_EQ(tested.heading_rad2_per_m(), 0.0);
  EXPECT_EQ(tested.position_m2_per_m(), 0.0);
  EXPECT_LT(tested.heading_test_statistic(), 6.635);
  EXPECT_NEAR(std::sqrt(tested.heading_jitter_rad2()), 0.014, 0.0035);  // 12.7 mrad found
}

// What closures erring by 20 mrad beside that jitter can tell at the default test (99.9 %): ten
// find an odometry of 3e-4 rad²/m (the Radish noisy logs' are 3.4e-4–1.9e-3, ACES's 3.3e-4) and
// one of 1e-4 (within a factor of two). Five do not find 3e-4 (the statistic is 7.3, which 99 %
// took), nor nineteen 1e-5: such an odometry is trusted as perfect until more closures disprove
// it.
TEST(OdometryModel, TenClosuresFindAnOdometryOf3e4Or1e4AndFiveDoNot) {
  const double jitter_rad = 0.014, closure_rad = 0.02;
  EXPECT_NEAR(
      Learned(MakeDrive(3e-4, 1.2e-3, 0.0, jitter_rad), {}, closure_rad, 60).heading_rad2_per_m(),
      3e-4, 0.5 * 3e-4);
  const double found =
      Learned(MakeDrive(1e-4, 4e-4, 0.0, jitter_rad), {}, closure_rad, 60).heading_rad2_per_m();
  EXPECT_GT(found, 0.5e-4);
  EXPECT_LT(found, 2e-4);
  const OdometryModel five =
      Learned(MakeDrive(3e-4, 1.2e-3, 0.0, jitter_rad), {}, closure_rad, 120);
  EXPECT_EQ(five.heading_rad2_per_m(), 0.0);
  EXPECT_GT(five.heading_test_statistic(), 6.635);
  EXPECT_EQ(
      Learned(MakeDrive(1e-5, 4e-5, 0.0, jitter_rad), {}, closure_rad, 30).heading_rad2_per_m(),
      0.0);
}

TEST(OdometryModel, AStepsShapeGrowsWithItsLengthAndTurnAndTheOptionsAreChecked) {
  const OdometryModel model{OdometryModelOptions{}};
  const OdometryStepShape shape = model.Shape(Pose2D(0.6, 0.8, -0.5));
  EXPECT_DOUBLE_EQ(shape.position(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(shape.position(1, 1), 1.0);
  EXPECT_DOUBLE_EQ(shape.heading(2, 2), 1.5);  // 1 m and 0.5 rad at 1 m per rad
  EXPECT_FALSE(model.learned());
  OdometryModelOptions bad;
  bad.floor_rad = 0.0;
  EXPECT_THROW(OdometryModel{bad}, std::invalid_argument);
  bad = {};
  bad.stretch_m = -1.0;
  EXPECT_THROW(OdometryModel{bad}, std::invalid_argument);
  bad = {};
  bad.heading_test_chi2 = -1.0;
  EXPECT_THROW(OdometryModel{bad}, std::invalid_argument);
  bad = {};
  bad.position_test_chi2 = -1.0;
  EXPECT_THROW(OdometryModel{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
