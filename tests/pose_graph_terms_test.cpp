// The pose graph's hand-written derivatives against automatic differentiation of the same
// formulas: bit for bit, so that a graph solves exactly as it did with Ceres' autodiff.

#include "graph/pose_graph_terms.hpp"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>

namespace scanloc {
namespace {

// The references: the terms as the pose graph wrote them for automatic differentiation.
template <typename T>
T WrapAngle(const T& angle_rad) {
  const T two_pi(2.0 * M_PI);
  return angle_rad - two_pi * ceres::floor((angle_rad + T(M_PI)) / two_pi);
}

struct PosturePlus {
  template <typename T>
  bool Plus(const T* posture, const T* delta, T* result) const {
    result[0] = posture[0] + delta[0];
    result[1] = posture[1] + delta[1];
    result[2] = WrapAngle(posture[2] + delta[2]);
    return true;
  }
  template <typename T>
  bool Minus(const T* to, const T* from, T* result) const {
    result[0] = to[0] - from[0];
    result[1] = to[1] - from[1];
    result[2] = WrapAngle(to[2] - from[2]);
    return true;
  }
};

class RelativePostureError {
 public:
  RelativePostureError(const Pose2D& measured, const Eigen::Matrix3d& sqrt_information)
      : measured_(measured), sqrt_information_(sqrt_information) {}
  template <typename T>
  bool operator()(const T* from, const T* to, T* residual) const {
    const T c = ceres::cos(from[2]), s = ceres::sin(from[2]);
    const T dx = to[0] - from[0], dy = to[1] - from[1];
    Eigen::Matrix<T, 3, 1> error;
    error << c * dx + s * dy - T(measured_.x_m), -s * dx + c * dy - T(measured_.y_m),
        WrapAngle(to[2] - from[2] - T(measured_.yaw_rad));
    Eigen::Map<Eigen::Matrix<T, 3, 1>> whitened(residual);
    whitened = sqrt_information_.template cast<T>() * error;
    return true;
  }

 private:
  Pose2D measured_;
  Eigen::Matrix3d sqrt_information_;
};

// Postures over ±50 m with headings anywhere, some a hair from ±π.
double RandomYaw(std::mt19937& rng) {
  std::uniform_real_distribution<double> any(-M_PI, M_PI), hair(-1e-9, 1e-9);
  std::bernoulli_distribution near_seam(0.2);
  return near_seam(rng) ? M_PI + hair(rng) : any(rng);
}

TEST(PoseGraphTerms, RelativePostureCostEqualsAutomaticDifferentiationBitForBit) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> position(-50.0, 50.0), entry(-3.0, 3.0),
      diagonal(0.1, 500.0);
  for (int trial = 0; trial < 5000; ++trial) {
    const double from[3] = {position(rng), position(rng), RandomYaw(rng)};
    const double to[3] = {position(rng), position(rng), RandomYaw(rng)};
    const Pose2D measured(entry(rng), entry(rng), RandomYaw(rng));
    Eigen::Matrix3d root = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 3; ++i) {
      root(i, i) = diagonal(rng);
      for (int j = i + 1; j < 3; ++j) root(i, j) = entry(rng);
    }
    const RelativePostureCost cost(measured, root);
    const ceres::AutoDiffCostFunction<RelativePostureError, 3, 3, 3> reference(
        new RelativePostureError(measured, root));
    const double* parameters[] = {from, to};
    double residual[3], expected[3], j_from[9], j_to[9], e_from[9], e_to[9];
    double* jacobians[] = {j_from, j_to};
    double* expected_jacobians[] = {e_from, e_to};
    ASSERT_TRUE(cost.Evaluate(parameters, residual, jacobians));
    ASSERT_TRUE(reference.Evaluate(parameters, expected, expected_jacobians));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(residual[i], expected[i]) << trial << " row " << i;
    for (int i = 0; i < 9; ++i) {
      EXPECT_EQ(j_from[i], e_from[i]) << trial << " from " << i;
      EXPECT_EQ(j_to[i], e_to[i]) << trial << " to " << i;
    }
    // Without Jacobians, or with one block's only, the residual is the same.
    double alone[3];
    ASSERT_TRUE(cost.Evaluate(parameters, alone, nullptr));
    double* only_to[] = {nullptr, j_to};
    ASSERT_TRUE(cost.Evaluate(parameters, alone, only_to));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(alone[i], expected[i]);
    for (int i = 0; i < 9; ++i) EXPECT_EQ(j_to[i], e_to[i]);
  }
}

TEST(PoseGraphTerms, PostureManifoldEqualsAutomaticDifferentiationBitForBit) {
  std::mt19937 rng(20);
  std::uniform_real_distribution<double> position(-50.0, 50.0), step(-0.5, 0.5);
  const PostureManifold manifold;
  const ceres::AutoDiffManifold<PosturePlus, 3, 3> reference;
  EXPECT_EQ(manifold.AmbientSize(), 3);
  EXPECT_EQ(manifold.TangentSize(), 3);
  for (int trial = 0; trial < 5000; ++trial) {
    const double x[3] = {position(rng), position(rng), RandomYaw(rng)};
    const double delta[3] = {step(rng), step(rng), step(rng)};
    double plus[3], expected[3];
    ASSERT_TRUE(manifold.Plus(x, delta, plus));
    ASSERT_TRUE(reference.Plus(x, delta, expected));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(plus[i], expected[i]) << trial;
    double minus[3], expected_minus[3];
    ASSERT_TRUE(manifold.Minus(plus, x, minus));
    ASSERT_TRUE(reference.Minus(plus, x, expected_minus));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(minus[i], expected_minus[i]) << trial;
    double jacobian[9], expected_jacobian[9];
    ASSERT_TRUE(manifold.PlusJacobian(x, jacobian));
    ASSERT_TRUE(reference.PlusJacobian(x, expected_jacobian));
    for (int i = 0; i < 9; ++i) EXPECT_EQ(jacobian[i], expected_jacobian[i]) << trial;
    ASSERT_TRUE(manifold.MinusJacobian(x, jacobian));
    ASSERT_TRUE(reference.MinusJacobian(x, expected_jacobian));
    for (int i = 0; i < 9; ++i) EXPECT_EQ(jacobian[i], expected_jacobian[i]) << trial;
  }
}

}  // namespace
}  // namespace scanloc
