#include "scanloc/session/odometry_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace scanloc {
namespace {

// Steps shorter than this (m, rad) say nothing of a scale and are left out of its fit.
constexpr double kMinStep = 1e-3;
// Huber's constant, in robust σ: 95 % efficiency on normal residuals.
constexpr double kHuber = 1.345;
constexpr int kIterations = 3;

}  // namespace

void OdometryCalibrationOptions::Validate() const {
  if (window < 1 || min_samples < 1 || refit_every < 1)
    throw std::invalid_argument(
        "OdometryCalibrationOptions: window, min_samples and refit_every must be >= 1");
  if (!(min_step_m >= 0.0 && min_step_rad >= 0.0 && std::isfinite(min_step_m + min_step_rad)))
    throw std::invalid_argument(
        "OdometryCalibrationOptions: min_step_m and min_step_rad must be finite and >= 0");
  if (!(min_change >= 0.0 && significance >= 0.0 && std::isfinite(min_change + significance)))
    throw std::invalid_argument(
        "OdometryCalibrationOptions: min_change and significance must be finite and >= 0");
  if (!(max_scale > 1.0 && std::isfinite(max_scale)))
    throw std::invalid_argument("OdometryCalibrationOptions: max_scale must be above 1");
}

OdometryCalibration::OdometryCalibration(OdometryCalibrationOptions options) : options_(options) {
  options_.Validate();
}

bool OdometryCalibration::Learn(const Pose2D& odometry_step, const Pose2D& matched_step) {
  if (!options_.enabled) return false;
  const double odometry_m = std::hypot(odometry_step.x_m, odometry_step.y_m);
  if (odometry_m < options_.min_step_m &&
      std::abs(NormalizeAngle(odometry_step.yaw_rad)) < options_.min_step_rad)
    return false;
  // The matched step along the odometry's direction: a scale error stretches the step, it does
  // not turn it.
  const double matched_m =
      odometry_m > 0.0
          ? (matched_step.x_m * odometry_step.x_m + matched_step.y_m * odometry_step.y_m) /
                odometry_m
          : 0.0;
  samples_.push_back({odometry_m, matched_m, NormalizeAngle(odometry_step.yaw_rad),
                      NormalizeAngle(matched_step.yaw_rad)});
  while (samples_.size() > static_cast<std::size_t>(options_.window)) samples_.pop_front();
  if (++since_fit_ >= static_cast<std::size_t>(options_.refit_every)) Refit();
  return true;
}

Pose2D OdometryCalibration::Calibrated(const Pose2D& odometry_step) const {
  return {distance_.value * odometry_step.x_m, distance_.value * odometry_step.y_m,
          NormalizeAngle(turn_.value * odometry_step.yaw_rad)};
}

void OdometryCalibration::Refit() {
  since_fit_ = 0;
  Fit(&Sample::odometry_m, &Sample::matched_m, distance_);
  Fit(&Sample::odometry_rad, &Sample::matched_rad, turn_);
}

// matched ≈ scale · odometry through the origin, by iteratively reweighted least squares with
// Huber weights on the residuals' robust σ (1.4826 · their median magnitude).
void OdometryCalibration::Fit(double Sample::*odometry, double Sample::*matched,
                              OdometryScale& scale) const {
  std::vector<const Sample*> moved;
  for (const Sample& s : samples_)
    if (std::abs(s.*odometry) > kMinStep) moved.push_back(&s);
  scale.samples = moved.size();
  if (moved.size() < static_cast<std::size_t>(options_.min_samples)) return;
  // Least squares first, then Huber's weights.
  double weighed = 0.0, information = 0.0, sigma = 0.0;
  for (const Sample* s : moved) {
    weighed += (s->*odometry) * (s->*matched);
    information += (s->*odometry) * (s->*odometry);
  }
  double value = weighed / information;
  std::vector<double> residuals(moved.size());
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    for (std::size_t i = 0; i < moved.size(); ++i)
      residuals[i] = std::abs(moved[i]->*matched - value * (moved[i]->*odometry));
    std::vector<double> sorted = residuals;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    sigma = std::max(1.4826 * sorted[sorted.size() / 2], 1e-9);
    weighed = 0.0;
    information = 0.0;
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const double w = std::min(1.0, kHuber * sigma / std::max(residuals[i], 1e-12));
      const double o = moved[i]->*odometry;
      weighed += w * o * (moved[i]->*matched);
      information += w * o * o;
    }
    if (!(information > 0.0)) return;
    value = weighed / information;
  }
  if (!std::isfinite(value)) return;
  scale.fitted = value;
  scale.standard_error = sigma / std::sqrt(information);
  const double change = std::abs(value - 1.0);
  scale.significant = value <= options_.max_scale && value >= 1.0 / options_.max_scale &&
                      change > options_.min_change &&
                      change > options_.significance * scale.standard_error;
  scale.value = scale.significant && options_.apply ? value : 1.0;
}

}  // namespace scanloc
