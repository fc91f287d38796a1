#include "scanloc/session/correction_gate.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/LU>

namespace scanloc {
namespace {

// Below these a median says the map and the odometry agree to within the matcher's noise; the
// floors keep a run of identical postures from closing the gate to nothing.
constexpr double kFloorM = 1e-3;
constexpr double kFloorRad = 1e-3;

}  // namespace

void CorrectionGateOptions::Validate() const {
  if (!(std::isfinite(factor) && factor >= 0.0))
    throw std::invalid_argument("CorrectionGateOptions: factor must be finite and >= 0");
  if (window < 0 || min_samples < 1)
    throw std::invalid_argument("CorrectionGateOptions: window >= 0 and min_samples >= 1");
  if (!(agree_factor >= 0.0 && std::isfinite(agree_factor)))
    throw std::invalid_argument("CorrectionGateOptions: agree_factor must be finite and >= 0");
  if (!(overlap_fraction >= 0.0 && overlap_fraction <= 1.0))
    throw std::invalid_argument("CorrectionGateOptions: overlap_fraction must be in [0, 1]");
  if (!(weak_axis_ratio >= 1.0))
    throw std::invalid_argument("CorrectionGateOptions: weak_axis_ratio must be >= 1");
}

bool CorrectionBound::Exceeded(const Pose2D& correction) const {
  return ExceededInPosition(correction) || ExceededInHeading(correction);
}

bool CorrectionBound::ExceededInHeading(const Pose2D& correction) const {
  return std::abs(NormalizeAngle(correction.yaw_rad)) > rotation_rad;
}

bool CorrectionBound::ExceededInPosition(const Pose2D& correction) const {
  return std::hypot(correction.x_m, correction.y_m) > translation_m;
}

double WeakAxisRatio(const Eigen::Matrix2d& covariance, const Eigen::Vector2d& direction) {
  const double norm2 = direction.squaredNorm();
  const Eigen::Matrix2d sym = 0.5 * (covariance + covariance.transpose());
  const double half_trace = 0.5 * sym.trace();
  const double smallest =
      half_trace - std::sqrt(std::max(0.0, half_trace * half_trace - sym.determinant()));
  if (!(norm2 > 0.0) || !(smallest > 0.0)) return 0.0;
  return std::sqrt(direction.dot(sym * direction) / norm2 / smallest);
}

void CorrectionGate::Add(const Pose2D& correction, double match_ratio) {
  if (options_.window == 0) return;
  translations_m_.Push(std::hypot(correction.x_m, correction.y_m));
  rotations_rad_.Push(std::abs(NormalizeAngle(correction.yaw_rad)));
  match_ratios_.Push(match_ratio);
  while (translations_m_.size() > static_cast<std::size_t>(options_.window)) {
    translations_m_.PopOldest();
    rotations_rad_.PopOldest();
    match_ratios_.PopOldest();
  }
}

std::optional<CorrectionBound> CorrectionGate::Bound(int unconfirmed) const {
  if (options_.factor == 0.0 ||
      translations_m_.size() < static_cast<std::size_t>(options_.min_samples))
    return std::nullopt;
  const double scale = options_.factor * std::sqrt(1.0 + std::max(0, unconfirmed));
  return CorrectionBound{scale * std::max(kFloorM, translations_m_.UpperMedian()),
                         scale * std::max(kFloorRad, rotations_rad_.UpperMedian())};
}

bool CorrectionGate::Unvalidated(const RefinementSupport& support, int unconfirmed) const {
  return options_.refuse_unvalidated && !support.validated && unconfirmed > 0;
}

bool CorrectionGate::Unsupported(const CorrectionBound& bound, const Pose2D& prediction,
                                 const Pose2D& refined, const RefinementSupport& support,
                                 int unconfirmed) const {
  const Pose2D correction = Between(prediction, refined);
  if (!bound.Exceeded(correction)) return false;
  if (LowOverlap(support.match_ratio)) return true;  // (Bound needs min_samples as LowOverlap)
  if (Unvalidated(support, unconfirmed)) return true;
  // A slide: beyond the bound in position only (a turn where the odometry slipped moves the
  // position with the heading), along the weak axis or still under way.
  if (bound.ExceededInHeading(correction)) return false;
  return !support.converged || AlongWeakAxis(prediction, refined, support);
}

bool CorrectionGate::Refuses(const Pose2D& prediction, const Pose2D& refined,
                             const RefinementSupport& support, int unconfirmed) {
  const bool one_step = options_.unvalidated_one_step && Unvalidated(support, unconfirmed);
  const std::optional<CorrectionBound> bound = Bound(one_step ? 0 : unconfirmed);
  const std::optional<Pose2D> refused = std::exchange(refused_, std::nullopt);
  if (!bound || !Unsupported(*bound, prediction, refined, support, unconfirmed)) return false;
  // Two refinements the rules rejected within a stretch they reject agree on nothing: they
  // started from the same turned candidates, in the same place the scans do not fit.
  const double agree = options_.agree_factor / options_.factor;
  if (refused && !Unvalidated(support, unconfirmed) &&
      !CorrectionBound{agree * bound->translation_m, agree * bound->rotation_rad}.Exceeded(
          Between(*refused, refined)))
    return false;
  refused_ = refined;
  return true;
}

bool CorrectionGate::Slides(const Pose2D& prediction, const Pose2D& refined,
                            const RefinementSupport& support) const {
  return !support.converged && AlongWeakAxis(prediction, refined, support);
}

bool CorrectionGate::AlongWeakAxis(const Pose2D& prediction, const Pose2D& refined,
                                   const RefinementSupport& support) const {
  return support.position_covariance &&
         WeakAxisRatio(*support.position_covariance,
                       Eigen::Vector2d(refined.x_m - prediction.x_m,
                                       refined.y_m - prediction.y_m)) >= options_.weak_axis_ratio;
}

void CorrectionGate::Moved(const Pose2D& odometry_increment) {
  if (refused_) refused_ = *refused_ * odometry_increment;
}

bool CorrectionGate::LowOverlap(double match_ratio) const {
  return samples() >= static_cast<std::size_t>(options_.min_samples) &&
         match_ratio < options_.overlap_fraction * match_ratios_.UpperMedian();
}

}  // namespace scanloc
