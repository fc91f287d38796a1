#include "scanloc/session/recovery.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace scanloc {

void RecoveryOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("RecoveryOptions: ") + what);
  };
  auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  require(lost_after_unconfirmed >= 0, "lost_after_unconfirmed must be >= 0");
  require(non_negative(min_half_width_m) && non_negative(translation_error_per_m) &&
              non_negative(max_half_width_m) && min_half_width_m <= max_half_width_m,
          "the window's widths must be finite, >= 0, min <= max");
  require(non_negative(min_half_yaw_rad) && non_negative(heading_error_per_rad) &&
              non_negative(heading_error_per_m) && min_half_yaw_rad <= max_half_yaw_rad &&
              max_half_yaw_rad <= M_PI,
          "the window's heading ranges must be finite, >= 0, min <= max <= π");
  search.Validate();
}

void DriftTracker::Moved(const Pose2D& odometry_increment) {
  distance_m_ += std::hypot(odometry_increment.x_m, odometry_increment.y_m);
  turn_rad_ += std::abs(NormalizeAngle(odometry_increment.yaw_rad));
}

void DriftTracker::Localised(bool confirmed) {
  if (!confirmed) {
    ++unconfirmed_;
    return;
  }
  unconfirmed_ = 0;
  distance_m_ = turn_rad_ = 0.0;
}

SearchWindow DriftTracker::Window(const Pose2D& T_world_laser_predicted) const {
  const RecoveryOptions& o = options_;
  SearchWindow window;
  window.centre = T_world_laser_predicted;
  window.half_width_m =
      std::min(o.max_half_width_m, o.min_half_width_m + o.translation_error_per_m * distance_m_);
  window.half_yaw_rad =
      std::min(o.max_half_yaw_rad, o.min_half_yaw_rad + o.heading_error_per_rad * turn_rad_ +
                                       o.heading_error_per_m * distance_m_);
  return window;
}

}  // namespace scanloc
