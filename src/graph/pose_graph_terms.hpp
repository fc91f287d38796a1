#pragma once
// The pose graph's terms for Ceres, with their derivatives written out: a node's posture
// manifold and an edge's whitened error. Private to the library (src/, not include/): Ceres stays
// a private dependency of scanloc, and only the graph layer and its tests see this header.

#include <ceres/manifold.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <cmath>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

// An angle wrapped to [-π, π): a − 2π·⌊(a + π) / 2π⌋.
inline double WrapGraphAngle(double angle_rad) {
  const double two_pi = 2.0 * M_PI;
  return angle_rad - two_pi * std::floor((angle_rad + M_PI) / two_pi);
}

// A node's posture (x, y, yaw) as one parameter block: a step is added and the yaw wrapped, so the
// solver never sees the jump at ±π. The wrap moves by whole turns, so both Jacobians are the
// identity (as automatic differentiation of the same formulas gives them, to the bit).
class PostureManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 3; }
  int TangentSize() const override { return 3; }
  bool Plus(const double* posture, const double* delta, double* result) const override;
  bool PlusJacobian(const double* posture, double* jacobian) const override;
  bool Minus(const double* to, const double* from, double* result) const override;
  bool MinusJacobian(const double* posture, double* jacobian) const override;
};

// The whitened difference between an edge's measured relative posture and the one its two nodes
// give now, in the `from` node's frame: residual = U·e with Ω = UᵀU and
//   e = (c·dx + s·dy − mx, −s·dx + c·dy − my, wrap(θto − θfrom − mθ)),
//   c, s = cos θfrom, sin θfrom; (dx, dy) = to − from.
// ∂e/∂from = [−c −s (−s·dx + c·dy); s −c (−c·dx − s·dy); 0 0 −1], ∂e/∂to = [c s 0; −s c 0; 0 0 1].
class RelativePostureCost : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  RelativePostureCost(const Pose2D& measured, const Eigen::Matrix3d& sqrt_information)
      : measured_(measured), sqrt_information_(sqrt_information) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Pose2D measured_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace scanloc
