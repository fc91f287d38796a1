#include "beam_residuals.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace scanloc {

BeamsResidual::BeamsResidual(std::vector<BeamTerm> beams, bool cosine, BeamKernel kernel)
    : beams_(std::move(beams)), cosine_(cosine), kernel_(kernel) {
  set_num_residuals(kResiduals);
  mutable_parameter_block_sizes()->push_back(3);
}

bool BeamsResidual::Evaluate(double const* const* parameters, double* residuals,
                             double** jacobians) const {
  const double* pose = parameters[0];
  const double cos_heading = std::cos(pose[2]), sin_heading = std::sin(pose[2]);
  if (jacobians == nullptr) return EvaluateCost(pose, cos_heading, sin_heading, residuals);
  // JᵀJ of the corrected beams by its upper triangle (xx, xy, xθ, yy, yθ, θθ), summed by hand:
  // Eigen's rank update of a 3 × 3 is a call per beam.
  double upper[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // Jᵀẽ
  double squared_sum = 0.0;                            // Σẽ²
  double excess = 0.0;                                 // Σ(ρ − ẽ²)
  const bool cached = kernel_.robust() && CachedAt(pose);
  for (std::size_t k = 0; k < beams_.size(); ++k) {
    double e = 0.0;
    Eigen::Vector3d row;
    if (!beams_[k].Evaluate(pose, cos_heading, sin_heading, cosine_, e, row.data())) return false;
    if (kernel_.robust()) {
      const double squared = e * e;
      double rho[3];
      if (cached) {
        kernel_.Derivatives(squared, rho);
        rho[0] = cached_rho_[k];
      } else {
        kernel_.Evaluate(squared, rho);
      }
      const double sqrt_rho1 = std::sqrt(rho[1]);
      double residual_scaling = sqrt_rho1, jacobian_scaling = sqrt_rho1;
      if (squared != 0.0 && rho[2] > 0.0) {
        const double alpha = 1.0 - std::sqrt(1.0 + 2.0 * squared * rho[2] / rho[1]);
        residual_scaling = sqrt_rho1 / (1.0 - alpha);
        jacobian_scaling = sqrt_rho1 * (1.0 - alpha);
      }
      row *= jacobian_scaling;
      const double corrected = residual_scaling * e;
      excess += rho[0] - corrected * corrected;
      e = corrected;
    }
    upper[0] += row(0) * row(0);
    upper[1] += row(0) * row(1);
    upper[2] += row(0) * row(2);
    upper[3] += row(1) * row(1);
    upper[4] += row(1) * row(2);
    upper[5] += row(2) * row(2);
    gradient += e * row;
    squared_sum += e * e;
  }
  Eigen::Matrix3d information;
  information << upper[0], upper[1], upper[2], upper[1], upper[3], upper[4], upper[2], upper[4],
      upper[5];
  // information = V·Λ·Vᵀ: J' = Λ^½·Vᵀ and r' = Λ^-½·Vᵀ·Jᵀẽ (directions without information
  // carry none), so that J'ᵀJ' = JᵀJ and J'ᵀr' = Jᵀẽ; the remainder carries the rest of the cost.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(information);
  const Eigen::Vector3d& lambda = eigen.eigenvalues();
  const Eigen::Matrix3d& v = eigen.eigenvectors();
  const double floor = kMinRelativeInformation * std::max(0.0, lambda(2));
  double projected = 0.0;  // ‖r'‖²
  for (int i = 0; i < 3; ++i) {
    const bool informed = lambda(i) > floor && lambda(i) > 0.0;
    const double root = informed ? std::sqrt(lambda(i)) : 0.0;
    residuals[i] = informed ? v.col(i).dot(gradient) / root : 0.0;
    projected += residuals[i] * residuals[i];
    if (jacobians != nullptr && jacobians[0] != nullptr)
      for (int j = 0; j < 3; ++j) jacobians[0][3 * i + j] = root * v(j, i);
  }
  residuals[3] = std::sqrt(std::max(0.0, squared_sum - projected + excess));
  if (jacobians != nullptr && jacobians[0] != nullptr)
    for (int j = 0; j < 3; ++j) jacobians[0][9 + j] = 0.0;
  return true;
}

bool BeamsResidual::EvaluateCost(const double* pose, double cos_heading, double sin_heading,
                                 double* residuals) const {
  double sum = 0.0;  // Σρ(e²), or Σe² without a kernel
  cached_ = false;
  if (kernel_.robust()) cached_rho_.resize(beams_.size());
  for (std::size_t k = 0; k < beams_.size(); ++k) {
    double e = 0.0;
    if (!beams_[k].Evaluate(pose, cos_heading, sin_heading, cosine_, e, nullptr)) return false;
    const double squared = e * e;
    if (kernel_.robust()) {
      double rho[3];
      kernel_.Evaluate(squared, rho);
      cached_rho_[k] = rho[0];
      sum += rho[0];
    } else {
      sum += squared;
    }
  }
  if (kernel_.robust()) {
    std::copy(pose, pose + 3, cached_at_);
    cached_ = true;
  }
  residuals[0] = std::sqrt(std::max(0.0, sum));
  residuals[1] = residuals[2] = residuals[3] = 0.0;
  return true;
}

bool BeamsResidual::CachedAt(const double* pose) const {
  return cached_ && pose[0] == cached_at_[0] && pose[1] == cached_at_[1] &&
         pose[2] == cached_at_[2];
}

PriorResidual::PriorResidual(const Pose2D& mean, const Eigen::Vector3d& weights)
    : mean_(mean), weights_(weights) {}

bool PriorResidual::Evaluate(double const* const* parameters, double* residuals,
                             double** jacobians) const {
  const double* pose = parameters[0];
  const double c = std::cos(mean_.yaw_rad), s = std::sin(mean_.yaw_rad);
  const double dx = pose[0] - mean_.x_m, dy = pose[1] - mean_.y_m;
  residuals[0] = weights_(0) * (c * dx + s * dy);
  residuals[1] = weights_(1) * (-s * dx + c * dy);
  residuals[2] = weights_(2) * NormalizeAngle(pose[2] - mean_.yaw_rad);
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    const double rows[9] = {
        weights_(0) * c, weights_(0) * s, 0.0, -weights_(1) * s, weights_(1) * c, 0.0, 0.0, 0.0,
        weights_(2)};
    std::copy(rows, rows + 9, jacobians[0]);
  }
  return true;
}

}  // namespace scanloc
