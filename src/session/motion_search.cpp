#include "scanloc/session/motion_search.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace scanloc {

void MotionSearchOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("MotionSearchOptions: ") + what);
  };
  require(std::isfinite(scale) && scale > 0.0, "scale must be finite and > 0");
  require(scans >= 1, "scans must be >= 1");
  require(std::isfinite(min_half_width_m) && min_half_width_m >= 0.0 &&
              std::isfinite(min_half_yaw_rad) && min_half_yaw_rad >= 0.0 &&
              min_half_yaw_rad <= M_PI,
          "the minima must be finite, >= 0 (the heading's <= π)");
  require(std::isfinite(frozen_odometry_range_change_m) && frozen_odometry_range_change_m >= 0.0,
          "frozen_odometry_range_change_m must be finite and >= 0");
}

void MotionWindow::Add(const Pose2D& motion) {
  translations_m_.push_back(std::hypot(motion.x_m, motion.y_m));
  rotations_rad_.push_back(std::abs(NormalizeAngle(motion.yaw_rad)));
  if (translations_m_.size() > static_cast<std::size_t>(options_.scans)) {
    translations_m_.pop_front();
    rotations_rad_.pop_front();
  }
}

SearchWindow MotionWindow::Window(const Pose2D& T_world_laser, double initial_half_width_m,
                                  double initial_half_yaw_rad, double max_half_width_m,
                                  double max_half_yaw_rad) const {
  if (motions() < kMinMotions) return {T_world_laser, initial_half_width_m, initial_half_yaw_rad};
  const double largest_m = *std::max_element(translations_m_.begin(), translations_m_.end());
  const double largest_rad = *std::max_element(rotations_rad_.begin(), rotations_rad_.end());
  const double half_m = std::max(options_.min_half_width_m, options_.scale * largest_m);
  const double half_rad = std::max(options_.min_half_yaw_rad, options_.scale * largest_rad);
  return {T_world_laser, std::min(half_m, max_half_width_m), std::min(half_rad, max_half_yaw_rad)};
}

SearchWindow MotionWindow::Window(const Pose2D& T_world_laser,
                                  const RecoveryOptions& recovery) const {
  return Window(T_world_laser, recovery.min_half_width_m, recovery.min_half_yaw_rad,
                recovery.max_half_width_m, recovery.max_half_yaw_rad);
}

bool SearchesMotion(const Iteration& iteration, std::size_t scans_before,
                    const MotionSearchOptions& options) {
  return !iteration.odometry && scans_before > 0 && options.enabled;
}

bool FrozenOdometry::SetAside(const Iteration& given) {
  if (!given.odometry) return false;
  if (!first_) {
    first_ = given.odometry;
    if (range_change_m_ > 0.0) first_scan_ = given.scan;
    return false;
  }
  // A millimetre or a milliradian: an odometry at rest repeats its pose.
  const Pose2D since = Between(*first_, *given.odometry);
  moved_ = moved_ || std::hypot(since.x_m, since.y_m) > 1e-3 ||
           std::abs(NormalizeAngle(since.yaw_rad)) > 1e-3;
  if (moved_ || !first_scan_) {
    first_scan_.reset();
    return false;
  }
  if (found_frozen_) return true;
  const std::optional<double> change_m = MedianRangeChange(*first_scan_, given.scan);
  found_frozen_ = !change_m || *change_m > range_change_m_;
  return found_frozen_;
}

bool NeedsMotionSearch(const LocalisationResult& result, const Pose2D& from,
                       const MotionSearchOptions& options) {
  const RankedCandidate* kept = result.Kept();
  if (!result.validated() || kept == nullptr) return true;
  const Pose2D moved = Between(from, kept->T_world_robot);
  return std::hypot(moved.x_m, moved.y_m) > options.min_half_width_m ||
         std::abs(NormalizeAngle(moved.yaw_rad)) > options.min_half_yaw_rad;
}

const Iteration& WithoutOdometryIf(bool strip, const Iteration& given,
                                   std::optional<Iteration>& stripped) {
  if (!strip || !given.odometry) return given;
  stripped = given;
  stripped->odometry.reset();
  return *stripped;
}

std::optional<double> MedianRangeChange(const LaserScan& a, const LaserScan& b,
                                        std::size_t min_beams) {
  if (a.size() != b.size() || a.layout.angle_min_rad != b.layout.angle_min_rad ||
      a.layout.angle_increment_rad != b.layout.angle_increment_rad)
    return std::nullopt;
  std::vector<double> changes;
  changes.reserve(a.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a.IsValid(k) && b.IsValid(k)) changes.push_back(std::abs(a.ranges_m[k] - b.ranges_m[k]));
  if (changes.size() < std::max<std::size_t>(min_beams, 1)) return std::nullopt;
  const auto middle = changes.begin() + static_cast<std::ptrdiff_t>(changes.size() / 2);
  std::nth_element(changes.begin(), middle, changes.end());
  return *middle;
}

}  // namespace scanloc
