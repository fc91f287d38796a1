#include "pose_graph_terms.hpp"

namespace scanloc {

bool PostureManifold::Plus(const double* posture, const double* delta, double* result) const {
  result[0] = posture[0] + delta[0];
  result[1] = posture[1] + delta[1];
  result[2] = WrapGraphAngle(posture[2] + delta[2]);
  return true;
}

bool PostureManifold::PlusJacobian(const double*, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(jacobian).setIdentity();
  return true;
}

bool PostureManifold::Minus(const double* to, const double* from, double* result) const {
  result[0] = to[0] - from[0];
  result[1] = to[1] - from[1];
  result[2] = WrapGraphAngle(to[2] - from[2]);
  return true;
}

bool PostureManifold::MinusJacobian(const double*, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(jacobian).setIdentity();
  return true;
}

bool RelativePostureCost::Evaluate(double const* const* parameters, double* residuals,
                                   double** jacobians) const {
  const double* from = parameters[0];
  const double* to = parameters[1];
  const double c = std::cos(from[2]), s = std::sin(from[2]);
  const double dx = to[0] - from[0], dy = to[1] - from[1];
  const double e[3] = {c * dx + s * dy - measured_.x_m, -s * dx + c * dy - measured_.y_m,
                       WrapGraphAngle(to[2] - from[2] - measured_.yaw_rad)};
  const Eigen::Matrix3d& u = sqrt_information_;
  // Row `row` of U·v, summed as Eigen sums a coefficient of a small product: p0 + (p1 + p2).
  const auto whiten = [&u](const double* v, int row) {
    return u(row, 0) * v[0] + (u(row, 1) * v[1] + u(row, 2) * v[2]);
  };
  for (int i = 0; i < 3; ++i) residuals[i] = whiten(e, i);
  if (jacobians == nullptr) return true;
  // Columns of ∂e/∂from and ∂e/∂to, each whitened; the Jacobians are row-major 3 × 3.
  const double from_columns[3][3] = {
      {-c, s, 0.0}, {-s, -c, 0.0}, {-s * dx + c * dy, -c * dx - s * dy, -1.0}};
  const double to_columns[3][3] = {{c, -s, 0.0}, {s, c, 0.0}, {0.0, 0.0, 1.0}};
  for (int block = 0; block < 2; ++block) {
    if (jacobians[block] == nullptr) continue;
    const double(*columns)[3] = block == 0 ? from_columns : to_columns;
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) jacobians[block][3 * i + j] = whiten(columns[j], i);
  }
  return true;
}

}  // namespace scanloc
