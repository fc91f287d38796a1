#include "scanloc/geometry/laser_scan.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace scanloc {

std::size_t LaserScan::CountValid() const {
  std::size_t count = 0;
  for (std::size_t i = 0; i < ranges_m.size(); ++i) count += IsValid(i) ? 1 : 0;
  return count;
}

const BearingCosines& BearingCosinesOf(const ScanLayout& layout) {
  thread_local BearingCosines table;
  if (table.cos.size() == layout.beam_count && table.beam_count == layout.beam_count &&
      table.angle_min_rad == layout.angle_min_rad &&
      table.angle_increment_rad == layout.angle_increment_rad)
    return table;
  table.beam_count = layout.beam_count;
  table.angle_min_rad = layout.angle_min_rad;
  table.angle_increment_rad = layout.angle_increment_rad;
  table.cos.resize(layout.beam_count);
  table.sin.resize(layout.beam_count);
  for (std::size_t k = 0; k < layout.beam_count; ++k) {
    table.cos[k] = std::cos(layout.Bearing(k));
    table.sin[k] = std::sin(layout.Bearing(k));
  }
  return table;
}

Eigen::Vector2d LaserScan::Point(std::size_t beam) const {
  const double bearing = layout.Bearing(beam);
  return {ranges_m[beam] * std::cos(bearing), ranges_m[beam] * std::sin(bearing)};
}

void LaserScan::CheckConsistent() const {
  if (layout.beam_count > kMaxBeamsPerScan)
    throw std::invalid_argument("laser scan: " + std::to_string(layout.beam_count) +
                                " beams, at most " + std::to_string(kMaxBeamsPerScan) +
                                " expected (kMaxBeamsPerScan)");
  if (layout.beam_count != ranges_m.size())
    throw std::invalid_argument("laser scan: layout has " + std::to_string(layout.beam_count) +
                                " beams but " + std::to_string(ranges_m.size()) + " ranges");
  if (!reflectance.empty() && reflectance.size() != ranges_m.size())
    throw std::invalid_argument("laser scan: reflectance count differs from range count");
  if (!(layout.angle_increment_rad > 0.0) || !std::isfinite(layout.angle_increment_rad) ||
      layout.angle_increment_rad * static_cast<double>(layout.beam_count) > 2.0 * M_PI + 1e-6)
    throw std::invalid_argument(
        "laser scan: angular increment must be positive and the beams "
        "must span at most one revolution");
  if (!std::isfinite(layout.angle_min_rad))
    throw std::invalid_argument("laser scan: first bearing must be finite");
  if (!(layout.range_max_m > layout.range_min_m) || !std::isfinite(layout.range_max_m))
    throw std::invalid_argument("laser scan: need range_min_m < range_max_m < infinity");
}

ScanLayout MakeLayout(std::size_t beam_count, double fov_rad, double range_max_m) {
  if (beam_count < 2) throw std::invalid_argument("MakeLayout: need at least 2 beams");
  if (!(fov_rad > 0.0) || fov_rad > 2.0 * M_PI + 1e-9)
    throw std::invalid_argument("MakeLayout: field of view must be in (0, 2π]");
  ScanLayout layout;
  layout.beam_count = beam_count;
  const bool full_circle = fov_rad > 2.0 * M_PI - 1e-9;
  layout.angle_increment_rad = full_circle ? fov_rad / beam_count : fov_rad / (beam_count - 1);
  layout.angle_min_rad = -fov_rad / 2.0;
  layout.range_max_m = range_max_m;
  return layout;
}

}  // namespace scanloc
