#include "scanloc/io/odometry_reversal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace scanloc {
namespace {

constexpr double kTolerance = 1e-12;

void ExpectPose(const Pose2D& actual, const Pose2D& expected) {
  EXPECT_NEAR(actual.x_m, expected.x_m, kTolerance);
  EXPECT_NEAR(actual.y_m, expected.y_m, kTolerance);
  EXPECT_NEAR(actual.yaw_rad, expected.yaw_rad, kTolerance);
}

TEST(OdometryReversalRepair, ForwardIncrementsWhileEveryVelocityIsNegativeBecomeBackward) {
  OdometryReversalRepair repair;
  // Heading +90°: the log's pose advances along +y while the robot reverses.
  ExpectPose(repair.Repair({1.0, 1.0, M_PI / 2}), {1.0, 1.0, M_PI / 2});
  repair.AddVelocity(-0.5);
  repair.AddVelocity(-0.4);
  ExpectPose(repair.Repair({1.0, 1.1, M_PI / 2}), {1.0, 0.9, M_PI / 2});
  repair.AddVelocity(-0.5);
  ExpectPose(repair.Repair({1.0, 1.3, M_PI / 2}), {1.0, 0.7, M_PI / 2});
  EXPECT_EQ(repair.repaired(), 2u);
}

TEST(OdometryReversalRepair, AReversedArcKeepsItsRotationAndMirrorsItsTranslation) {
  OdometryReversalRepair repair;
  repair.Repair({0.0, 0.0, 0.0});
  repair.AddVelocity(-0.3);
  // Forward along an arc: 0.2 m turning by 0.1 rad.
  const double turn = 0.1, length = 0.2;
  const Pose2D arc{length * std::sin(turn) / turn, length * (1.0 - std::cos(turn)) / turn, turn};
  ExpectPose(repair.Repair(arc), {-arc.x_m, -arc.y_m, turn});
}

TEST(OdometryReversalRepair, LaterScansFollowOnFromTheRepairedPose) {
  OdometryReversalRepair repair;
  repair.Repair({0.0, 0.0, 0.0});
  repair.AddVelocity(-0.5);
  ExpectPose(repair.Repair({0.1, 0.0, 0.0}), {-0.1, 0.0, 0.0});
  repair.AddVelocity(0.5);  // forward again: the increment is kept, from the repaired pose
  ExpectPose(repair.Repair({0.3, 0.0, 0.2}), {0.1, 0.0, 0.2});
  EXPECT_EQ(repair.repaired(), 1u);
}

TEST(OdometryReversalRepair, IncrementsAreKeptUnlessEveryVelocitySinceTheLastScanIsNegative) {
  OdometryReversalRepair repair;
  repair.Repair({0.0, 0.0, 0.0});
  repair.AddVelocity(-0.5);
  repair.AddVelocity(0.2);  // the robot changed direction in between: the log is trusted
  ExpectPose(repair.Repair({0.1, 0.0, 0.0}), {0.1, 0.0, 0.0});
  ExpectPose(repair.Repair({0.2, 0.0, 0.0}), {0.2, 0.0, 0.0});  // no velocity logged
  repair.AddVelocity(-0.005);                                   // below the reversing speed
  ExpectPose(repair.Repair({0.3, 0.0, 0.0}), {0.3, 0.0, 0.0});
  repair.AddVelocity(-0.5);  // the log already moved backward: right as it is
  ExpectPose(repair.Repair({0.2, 0.0, 0.0}), {0.2, 0.0, 0.0});
  EXPECT_EQ(repair.repaired(), 0u);
}

TEST(OdometryReversalRepair, WithoutARepairTheLoggedPosesPassBitForBit) {
  OdometryReversalRepair repair;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0), angle(-M_PI, M_PI),
      velocity(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Pose2D logged{coordinate(random), coordinate(random), angle(random)};
    repair.AddVelocity(velocity(random));
    const Pose2D out = repair.Repair(logged);
    ASSERT_EQ(out.x_m, logged.x_m);
    ASSERT_EQ(out.y_m, logged.y_m);
    ASSERT_EQ(out.yaw_rad, logged.yaw_rad);
  }
}

}  // namespace
}  // namespace scanloc
