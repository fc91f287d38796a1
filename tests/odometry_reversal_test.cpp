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

TEST(OdometryReversalRepair, ForwardIncrementsWhileTheVelocityIsNegativeBecomeBackward) {
  OdometryReversalRepair repair;
  // Heading +90°: the log's pose advances along +y while the robot reverses.
  ExpectPose(repair.Follow({1.0, 1.0, M_PI / 2}, kNoVelocity), {1.0, 1.0, M_PI / 2});
  ExpectPose(repair.Follow({1.0, 1.05, M_PI / 2}, -0.5), {1.0, 0.95, M_PI / 2});
  ExpectPose(repair.Follow({1.0, 1.1, M_PI / 2}, -0.4), {1.0, 0.9, M_PI / 2});
  // A scan between ODOM messages takes the latest velocity logged.
  ExpectPose(repair.Follow({1.0, 1.3, M_PI / 2}, kNoVelocity), {1.0, 0.7, M_PI / 2});
  EXPECT_EQ(repair.repaired(), 3u);
}

TEST(OdometryReversalRepair, AReversedArcKeepsItsRotationAndMirrorsItsTranslation) {
  OdometryReversalRepair repair;
  repair.Follow({0.0, 0.0, 0.0}, kNoVelocity);
  // Forward along an arc: 0.2 m turning by 0.1 rad.
  const double turn = 0.1, length = 0.2;
  const Pose2D arc{length * std::sin(turn) / turn, length * (1.0 - std::cos(turn)) / turn, turn};
  ExpectPose(repair.Follow(arc, -0.3), {-arc.x_m, -arc.y_m, turn});
}

TEST(OdometryReversalRepair, LaterMessagesFollowOnFromTheRepairedPose) {
  OdometryReversalRepair repair;
  repair.Follow({0.0, 0.0, 0.0}, kNoVelocity);
  ExpectPose(repair.Follow({0.1, 0.0, 0.0}, -0.5), {-0.1, 0.0, 0.0});
  // Forward again: the increment is kept, from the repaired pose.
  ExpectPose(repair.Follow({0.3, 0.0, 0.2}, 0.5), {0.1, 0.0, 0.2});
  EXPECT_EQ(repair.repaired(), 1u);
}

// Scans a metre apart: between two of them the robot drives forward, stops and reverses. Each
// ODOM increment is judged by its own velocity, so the second scan's odometry is where the robot
// went, whatever the velocities over the whole interval.
TEST(OdometryReversalRepair, AScanAfterForwardAndReversedIncrementsIsWhereTheRobotWent) {
  OdometryReversalRepair repair;
  ExpectPose(repair.Follow({0.0, 0.0, 0.0}, kNoVelocity), {0.0, 0.0, 0.0});  // the first scan
  repair.Follow({0.5, 0.0, 0.0}, 0.5);                                       // forward 0.5 m
  repair.Follow({0.5, 0.0, 0.0}, 0.0);                                       // stopped
  repair.Follow({0.7, 0.0, 0.0}, -0.2);  // reversing, logged as forward
  repair.Follow({0.9, 0.0, 0.0}, -0.2);
  ExpectPose(repair.Follow({1.0, 0.0, 0.0}, kNoVelocity), {0.0, 0.0, 0.0});  // the next scan
  EXPECT_EQ(repair.repaired(), 3u);
}

TEST(OdometryReversalRepair, IncrementsAreKeptUnlessTheVelocityOverThemSaysReversing) {
  OdometryReversalRepair repair;
  repair.Follow({0.0, 0.0, 0.0}, kNoVelocity);
  ExpectPose(repair.Follow({0.1, 0.0, 0.0}, kNoVelocity), {0.1, 0.0, 0.0});  // none logged yet
  ExpectPose(repair.Follow({0.2, 0.0, 0.0}, 0.2), {0.2, 0.0, 0.0});
  ExpectPose(repair.Follow({0.3, 0.0, 0.0}, -0.005), {0.3, 0.0, 0.0});  // below reversing speed
  ExpectPose(repair.Follow({0.2, 0.0, 0.0}, -0.5), {0.2, 0.0, 0.0});    // already backward: right
  EXPECT_EQ(repair.repaired(), 0u);
}

TEST(OdometryReversalRepair, WithoutARepairTheLoggedPosesPassBitForBit) {
  OdometryReversalRepair repair;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0), angle(-M_PI, M_PI),
      velocity(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Pose2D logged{coordinate(random), coordinate(random), angle(random)};
    const Pose2D out = repair.Follow(logged, i % 3 == 0 ? kNoVelocity : velocity(random));
    ASSERT_EQ(out.x_m, logged.x_m);
    ASSERT_EQ(out.y_m, logged.y_m);
    ASSERT_EQ(out.yaw_rad, logged.yaw_rad);
  }
}

}  // namespace
}  // namespace scanloc
