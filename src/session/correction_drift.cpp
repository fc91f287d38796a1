#include "scanloc/session/correction_drift.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace scanloc {

void CorrectionDriftOptions::Validate() const {
  if (!(window_m >= 0.0) || !std::isfinite(window_m))
    throw std::invalid_argument("CorrectionDriftOptions: window_m must be finite and >= 0");
  if (!(factor > 0.0) || !std::isfinite(factor))
    throw std::invalid_argument("CorrectionDriftOptions: factor must be finite and > 0");
  if (samples < 1) throw std::invalid_argument("CorrectionDriftOptions: samples must be >= 1");
  if (min_samples < 1 || min_samples > samples)
    throw std::invalid_argument("CorrectionDriftOptions: min_samples must be in [1, samples]");
}

CorrectionDrift::CorrectionDrift(CorrectionDriftOptions options) : options_(options) {
  options_.Validate();
}

void CorrectionDrift::Predicted(const Pose2D& prediction) {
  step_m_ = last_ ? (prediction.Translation() - last_->Translation()).norm() : 0.0;
}

std::optional<SlideCheck> CorrectionDrift::Check(const Eigen::Vector2d& correction,
                                                 double floor_m) const {
  const std::optional<double> bound = Bound();
  if (!bound) return std::nullopt;
  const Eigen::Vector2d sum = Total();
  return SlideCheck{sum.norm(), (sum + correction).norm(), std::max(*bound, floor_m)};
}

void CorrectionDrift::Kept(const Pose2D& posture, const std::optional<Eigen::Vector2d>& correction,
                           bool held) {
  last_ = posture;
  if (!(options_.window_m > 0.0)) return;
  if (held) {
    held_m_ += step_m_;
    step_m_ = 0.0;
    return;
  }
  path_m_ += step_m_;
  while (!window_.empty() && path_m_ - window_.front().first > options_.window_m)
    window_.pop_front();
  step_m_ = 0.0;
  if (!correction) return;
  window_.emplace_back(path_m_, *correction);
  const double sum = Sum();
  if (sums_m_.size() >= static_cast<std::size_t>(options_.min_samples) &&
      sum <= options_.factor * sums_m_.UpperMedian())
    held_m_ = 0.0;
  sums_m_.Push(sum);
  if (sums_m_.size() > static_cast<std::size_t>(options_.samples)) sums_m_.PopOldest();
}

void CorrectionDrift::Moved(const Pose2D& posture) {
  if (last_) last_ = posture;
}

void CorrectionDrift::Restart(const Pose2D& posture) {
  last_ = posture;
  window_.clear();
  step_m_ = held_m_ = 0.0;
}

double CorrectionDrift::Sum() const {
  return Total().norm();
}

std::optional<double> CorrectionDrift::Bound() const {
  if (!(options_.window_m > 0.0) || sums_m_.size() < static_cast<std::size_t>(options_.min_samples))
    return std::nullopt;
  return options_.factor * sums_m_.UpperMedian() * std::sqrt(1.0 + held_m_ / options_.window_m);
}

Eigen::Vector2d CorrectionDrift::Total() const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const auto& [path_m, correction] : window_)
    if (path_m_ + step_m_ - path_m <= options_.window_m) sum += correction;
  return sum;
}

}  // namespace scanloc
