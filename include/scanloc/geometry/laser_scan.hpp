#pragma once
// A planar laser scan: N ranges at evenly spaced bearings, in the laser's own frame.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

// The most beams a scan may have: readers refuse more. A 360° laser at 0.01° has 36,000 beams;
// 100,000 leaves room for any real laser while a malformed count cannot claim gigabytes.
constexpr std::size_t kMaxBeamsPerScan = 100000;

// The angular layout and range limits shared by a real scan and the scans simulated for it.
struct ScanLayout {
  std::size_t beam_count = 0;        // number of beams
  double angle_min_rad = 0.0;        // bearing of beam 0 in the laser frame
  double angle_increment_rad = 0.0;  // bearing step between consecutive beams (> 0)
  double range_min_m = 0.0;          // ranges at or below this carry no echo
  double range_max_m = 20.0;         // ranges at or beyond this carry no echo (the Acuity's 20 m)

  double Bearing(std::size_t beam) const { return angle_min_rad + beam * angle_increment_rad; }
};

struct LaserScan {
  ScanLayout layout;
  std::vector<double> ranges_m;     // the trials coded "no echo" as -1.0
  std::vector<double> reflectance;  // empty, or one value per beam
  double timestamp_s = 0.0;

  std::size_t size() const { return ranges_m.size(); }
  // Throws std::invalid_argument unless the layout is usable (at most kMaxBeamsPerScan beams) and
  // matches the ranges (and the reflectance, when present).
  void CheckConsistent() const;
  // A range is valid when finite, above range_min_m and below range_max_m.
  bool IsValid(std::size_t beam) const;
  std::size_t CountValid() const;
  // The beam's end point in the laser frame (meaningful for valid beams only).
  Eigen::Vector2d Point(std::size_t beam) const;
};

// The cosine and sine of each bearing of a layout, bit for bit std::cos and std::sin of
// Bearing(k) (so r·(cos[k], sin[k]) is LaserScan::Point(k)).
struct BearingCosines {
  std::size_t beam_count = 0;
  double angle_min_rad = 0.0, angle_increment_rad = 0.0;
  std::vector<double> cos, sin;
};
// The table of the layout last asked for on this thread, computed when the layout changes (every
// scan of a log has the same). The reference holds until the next call with another layout.
const BearingCosines& BearingCosinesOf(const ScanLayout& layout);

// True when the range is finite, above range_min_m and below range_max_m. Inline: it is asked
// once per beam almost everywhere.
inline bool IsValidRange(double range_m, const ScanLayout& layout) {
  return std::isfinite(range_m) && range_m > 0.0 && range_m > layout.range_min_m &&
         range_m < layout.range_max_m;
}
inline bool LaserScan::IsValid(std::size_t beam) const {
  return IsValidRange(ranges_m[beam], layout);
}

// A layout of `beam_count` beams over `fov_rad`, centred on the heading. For a full revolution
// (fov = 2π) the last beam stops one step short of the first.
ScanLayout MakeLayout(std::size_t beam_count, double fov_rad, double range_max_m);

// False when the bearings [lo, hi] (relative to angle_min_rad) certainly hold no beam: hi is
// more than a millionth of a step below beam 0, or lo as far above the last beam. The intervals'
// own tolerance is a billionth of a step, so such a shift would visit nothing: skipping its
// divisions changes no result.
inline bool IntervalMayHoldBeams(const ScanLayout& layout, double lo, double hi) {
  const double inc = layout.angle_increment_rad;
  return hi >= -1e-6 * inc && lo <= (static_cast<double>(layout.beam_count) - 1.0 + 1e-6) * inc;
}

// Calls visit(beam) for each beam of `layout` whose bearing (laser frame) lies in
// [from, from + span], span in [0, π]; bearings are compared modulo 2π so an interval across the
// ±π seam is handled.
template <class Visit>
void ForEachBeamInInterval(const ScanLayout& layout, double from_rad, double span_rad,
                           Visit visit) {
  const double inc = layout.angle_increment_rad;
  const double start = NormalizeAngle(from_rad);
  for (const double shift : {-2.0 * M_PI, 0.0, 2.0 * M_PI}) {
    const double lo = start + shift - layout.angle_min_rad;
    const double hi = lo + span_rad;
    if (!IntervalMayHoldBeams(layout, lo, hi)) continue;
    const double first = std::max(0.0, std::ceil(lo / inc - 1e-9));
    const double last =
        std::min(static_cast<double>(layout.beam_count) - 1.0, std::floor(hi / inc + 1e-9));
    for (double k = first; k <= last; k += 1.0) visit(static_cast<std::size_t>(k));
  }
}

// True when test(beam) holds for some beam of `layout` in [from, from + span] (as
// ForEachBeamInInterval); stops at the first.
template <class Test>
bool AnyBeamInInterval(const ScanLayout& layout, double from_rad, double span_rad, Test test) {
  const double inc = layout.angle_increment_rad;
  const double start = NormalizeAngle(from_rad);
  for (const double shift : {-2.0 * M_PI, 0.0, 2.0 * M_PI}) {
    const double lo = start + shift - layout.angle_min_rad;
    if (!IntervalMayHoldBeams(layout, lo, lo + span_rad)) continue;
    const double first = std::max(0.0, std::ceil(lo / inc - 1e-9));
    const double last = std::min(static_cast<double>(layout.beam_count) - 1.0,
                                 std::floor((lo + span_rad) / inc + 1e-9));
    for (double k = first; k <= last; k += 1.0)
      if (test(static_cast<std::size_t>(k))) return true;
  }
  return false;
}

// The laser's fixed mounting on the robot: T_robot_laser. Postures are reported in robot
// coordinates; scans are simulated from T_world_laser = T_world_robot * T_robot_laser.
struct LaserMounting {
  Pose2D T_robot_laser;
  Pose2D LaserPose(const Pose2D& T_world_robot) const { return T_world_robot * T_robot_laser; }
  Pose2D RobotPose(const Pose2D& T_world_laser) const {
    return T_world_laser * T_robot_laser.Inverse();
  }
};

}  // namespace scanloc
