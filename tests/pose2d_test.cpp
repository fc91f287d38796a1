#include "scanloc/geometry/pose2d.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace scanloc {
namespace {

TEST(NormalizeAngle, WrapsIntoHalfOpenMinusPiPi) {
  EXPECT_DOUBLE_EQ(NormalizeAngle(0.5), 0.5);
  EXPECT_NEAR(NormalizeAngle(3.0 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-3.5 * M_PI), 0.5 * M_PI, 1e-12);
  EXPECT_NEAR(NormalizeAngle(2.0 * M_PI + 0.1), 0.1, 1e-12);
}

TEST(NormalizeAngle, FastPathEqualsRemainderBitForBit) {
  // The inline fast path must give std::remainder's result exactly: sessions are compared byte
  // for byte across builds.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> wide(-30.0, 30.0);
  std::vector<double> angles = {M_PI,
                                -M_PI,
                                3.0 * M_PI,
                                -3.0 * M_PI,
                                9.0,
                                -9.0,
                                std::nextafter(M_PI, 10.0),
                                std::nextafter(-M_PI, -10.0),
                                std::nextafter(9.0, 0.0),
                                std::nextafter(-9.0, 0.0),
                                0.0,
                                -0.0};
  for (int i = 0; i < 200000; ++i) angles.push_back(wide(rng));
  for (const double a : angles) {
    const double fast = NormalizeAngle(a), slow = NormalizeAngleSlow(a);
    ASSERT_EQ(std::memcmp(&fast, &slow, sizeof fast), 0) << "angle " << a;
  }
  EXPECT_TRUE(std::isnan(NormalizeAngle(std::nan(""))));
  EXPECT_TRUE(std::isinf(NormalizeAngle(INFINITY)));
}

TEST(Pose2D, ComposeMatchesHandComputedTransform) {
  const Pose2D a{1.0, 2.0, M_PI / 2.0};
  const Pose2D b{3.0, 0.0, 0.25};
  const Pose2D c = a * b;
  EXPECT_NEAR(c.x_m, 1.0, 1e-12);
  EXPECT_NEAR(c.y_m, 5.0, 1e-12);
  EXPECT_NEAR(c.yaw_rad, M_PI / 2.0 + 0.25, 1e-12);
}

TEST(Pose2D, InverseComposesToIdentityOnRandomPoses) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  for (int i = 0; i < 100; ++i) {
    const Pose2D p{u(rng), u(rng), u(rng)};
    const Pose2D identity = p * p.Inverse();
    EXPECT_NEAR(identity.x_m, 0.0, 1e-9);
    EXPECT_NEAR(identity.y_m, 0.0, 1e-9);
    EXPECT_NEAR(identity.yaw_rad, 0.0, 1e-12);
  }
}

TEST(Pose2D, BetweenRecoversTheRelativeMotion) {
  const Pose2D from{2.0, -1.0, 2.5};
  const Pose2D motion{0.3, 0.1, -0.2};
  const Pose2D to = from * motion;
  const Pose2D recovered = Between(from, to);
  EXPECT_NEAR(recovered.x_m, 0.3, 1e-12);
  EXPECT_NEAR(recovered.y_m, 0.1, 1e-12);
  EXPECT_NEAR(recovered.yaw_rad, -0.2, 1e-12);
}

TEST(Pose2D, TransformMapsLaserPointToWorld) {
  const Pose2D T_world_laser{1.0, 1.0, M_PI};
  const Eigen::Vector2d p = T_world_laser.Transform({2.0, 0.0});
  EXPECT_NEAR(p.x(), -1.0, 1e-12);
  EXPECT_NEAR(p.y(), 1.0, 1e-12);
}

// Taking the cosine and sine once must not change a single bit of the transformed points.
TEST(PoseTransform, MapsPointsBitForBitAsPose2DTransform) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0), angle(-10.0, 10.0);
  for (int i = 0; i < 2000; ++i) {
    const Pose2D pose(coordinate(rng), coordinate(rng), angle(rng));
    const PoseTransform transform(pose);
    const Eigen::Vector2d point(coordinate(rng), coordinate(rng));
    const Eigen::Vector2d a = pose.Transform(point), b = transform(point);
    EXPECT_EQ(a.x(), b.x()) << i;
    EXPECT_EQ(a.y(), b.y()) << i;
  }
}

}  // namespace
}  // namespace scanloc
