#include "scanloc/io/odometry_reversal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

namespace scanloc {
namespace {

constexpr double kTolerance = 1e-12;
constexpr std::optional<double> kNoVelocity;  // a FLASER: its odometry without a velocity

void ExpectPose(const Pose2D& actual, const Pose2D& expected) {
  EXPECT_NEAR(actual.x_m, expected.x_m, kTolerance);
  EXPECT_NEAR(actual.y_m, expected.y_m, kTolerance);
  EXPECT_NEAR(actual.yaw_rad, expected.yaw_rad, kTolerance);
}

// ODOM messages and FLASER scans in one frame, 0.1 s apart.
TEST(OdometryReversalRepair, ForwardOdometryIncrementsWhileTheVelocityIsNegativeBecomeBackward) {
  OdometryReversalRepair repair;
  // Heading +90°: the log's pose advances along +y while the robot reverses.
  repair.AddOdometry({1.0, 1.0, M_PI / 2}, 0.0, 0.0);
  ExpectPose(repair.Repair({1.0, 1.0, M_PI / 2}, kNoVelocity, 0.05), {1.0, 1.0, M_PI / 2});
  repair.AddOdometry({1.0, 1.05, M_PI / 2}, -0.5, 0.1);
  repair.AddOdometry({1.0, 1.1, M_PI / 2}, -0.5, 0.2);
  ExpectPose(repair.Repair({1.0, 1.1, M_PI / 2}, kNoVelocity, 0.25), {1.0, 0.9, M_PI / 2});
  EXPECT_EQ(repair.repaired(), 2u);
}

TEST(OdometryReversalRepair, AReversedArcKeepsItsRotationAndMirrorsItsTranslation) {
  OdometryReversalRepair repair;
  repair.AddOdometry({0.0, 0.0, 0.0}, 0.0, 0.0);
  // Forward along an arc: 0.2 m turning by 0.1 rad.
  const double turn = 0.1, length = 0.2;
  const Pose2D arc{length * std::sin(turn) / turn, length * (1.0 - std::cos(turn)) / turn, turn};
  repair.AddOdometry(arc, -0.3, 0.5);
  ExpectPose(repair.Repair(arc, kNoVelocity, 0.5), {-arc.x_m, -arc.y_m, turn});
}

TEST(OdometryReversalRepair, LaterScansFollowOnFromTheRepairedPose) {
  OdometryReversalRepair repair;
  repair.AddOdometry({0.0, 0.0, 0.0}, 0.0, 0.0);
  repair.AddOdometry({0.1, 0.0, 0.0}, -0.5, 0.2);
  ExpectPose(repair.Repair({0.1, 0.0, 0.0}, kNoVelocity, 0.2), {-0.1, 0.0, 0.0});
  repair.AddOdometry({0.3, 0.0, 0.2}, 0.5, 0.6);  // forward again: kept, from the repaired pose
  ExpectPose(repair.Repair({0.3, 0.0, 0.2}, kNoVelocity, 0.6), {0.1, 0.0, 0.2});
  EXPECT_EQ(repair.repaired(), 1u);
}

// Scans a metre apart: between two of them the robot drives forward, stops and reverses. Each
// ODOM increment is judged by its own velocity, so the second scan's odometry is where the robot
// went, whatever the velocities over the whole interval.
TEST(OdometryReversalRepair, AScanAfterForwardAndReversedIncrementsIsWhereTheRobotWent) {
  OdometryReversalRepair repair;
  repair.AddOdometry({0.0, 0.0, 0.0}, 0.0, 0.0);
  ExpectPose(repair.Repair({0.0, 0.0, 0.0}, kNoVelocity, 0.0), {0.0, 0.0, 0.0});
  repair.AddOdometry({0.5, 0.0, 0.0}, 0.5, 1.0);   // forward 0.5 m
  repair.AddOdometry({0.5, 0.0, 0.0}, 0.0, 1.5);   // stopped
  repair.AddOdometry({0.7, 0.0, 0.0}, -0.2, 2.5);  // reversing, logged as forward
  repair.AddOdometry({0.9, 0.0, 0.0}, -0.2, 3.5);
  ExpectPose(repair.Repair({0.9, 0.0, 0.0}, kNoVelocity, 3.5), {0.1, 0.0, 0.0});
  EXPECT_EQ(repair.repaired(), 2u);
}

// A log whose scans' pose fields were never filled in (all zero) while its ODOM messages move and
// reverse: the scans are not in the ODOM messages' frame, so they keep their own (still) odometry.
TEST(OdometryReversalRepair, ScansOutsideTheOdometryFrameKeepTheirOwnChain) {
  OdometryReversalRepair repair;
  for (int i = 0; i < 20; ++i) {
    const double t = 0.1 * i;
    repair.AddOdometry({5.0 + 0.05 * i, 3.0, 0.0}, -0.5, t);
    ExpectPose(repair.Repair({0.0, 0.0, 0.0}, kNoVelocity, t), {0.0, 0.0, 0.0});
  }
  EXPECT_EQ(repair.repaired(), 19u);  // the ODOM chain's, which the scans do not follow
}

// Without ODOM messages (ROBOTLASER1 scans carry their own velocity), a scan's increment is
// reversed only when every velocity since the scan before says the robot reversed.
TEST(OdometryReversalRepair, WithoutOdometryMessagesAScanIsJudgedByItsOwnVelocity) {
  OdometryReversalRepair repair;
  repair.Repair({0.0, 0.0, 0.0}, 0.0, 0.0);
  ExpectPose(repair.Repair({0.1, 0.0, 0.0}, -0.5, 0.2), {-0.1, 0.0, 0.0});
  ExpectPose(repair.Repair({0.2, 0.0, 0.0}, 0.2, 0.4), {0.0, 0.0, 0.0});     // forward: kept
  ExpectPose(repair.Repair({0.3, 0.0, 0.0}, -0.005, 0.6), {0.1, 0.0, 0.0});  // below reversing
  ExpectPose(repair.Repair({0.2, 0.0, 0.0}, -0.5, 0.8), {0.0, 0.0, 0.0});    // already backward
  EXPECT_EQ(repair.repaired(), 1u);
}

TEST(OdometryReversalRepair, WithoutARepairTheLoggedPosesPassBitForBit) {
  OdometryReversalRepair repair;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0), angle(-M_PI, M_PI),
      velocity(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Pose2D logged{coordinate(random), coordinate(random), angle(random)};
    if (i % 2 == 0) repair.AddOdometry(logged, velocity(random), 0.1 * i);
    const Pose2D out = repair.Repair(logged, i % 3 == 0 ? kNoVelocity : velocity(random), 0.1 * i);
    ASSERT_EQ(out.x_m, logged.x_m);
    ASSERT_EQ(out.y_m, logged.y_m);
    ASSERT_EQ(out.yaw_rad, logged.yaw_rad);
  }
}

}  // namespace
}  // namespace scanloc
