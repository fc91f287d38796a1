#pragma once
// A bearing cheaper than std::atan2, within a stated bound of it: for culls that must be exact,
// which widen their interval by more than the bound and ask std::atan2 only when the cull fails.

#include <cmath>
#include <cstddef>

#include <Eigen/Core>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

// The bound on |ApproximateAtan2(y, x) − std::atan2(y, x)| modulo 2π, radians, for finite
// (x, y) ≠ (0, 0) (at y = −0 with x < 0 one says π and the other −π). Abramowitz & Stegun 4.4.49
// give 1e-5 for the polynomial; with its seven-digit coefficients the sweep in
// tests/approximate_bearing_test.cpp finds at most 1.15e-5.
constexpr double kApproximateAtan2Bound = 1.5e-5;

// atan2(y, x) in [−π, π] from the octant and A&S 4.4.49's odd polynomial on [0, 1].
inline double ApproximateAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double t = ax >= ay ? ay / ax : ax / ay;  // in [0, 1]
  const double t2 = t * t;
  double a =
      t * (0.9998660 + t2 * (-0.3302995 + t2 * (0.1801410 + t2 * (-0.0851330 + t2 * 0.0208351))));
  if (ay > ax) a = 0.5 * M_PI - a;
  if (x < 0.0) a = M_PI - a;
  return y < 0.0 ? -a : a;
}

// The beam nearest the bearing of `q` (a point in the laser's frame) among n beams from angle_min
// by increment, as a rounded position (possibly outside [0, n − 1]): std::round of the position of
// q's std::atan2 bearing, bit for bit. ApproximateAtan2 decides unless the position lies within its
// bound of a half step between beams (or of the turn behind a full revolution's laser, a half step
// there too); then std::atan2 does.
inline double NearestBeamPosition(const Eigen::Vector2d& q, double angle_min, double increment,
                                  std::size_t n) {
  const double middle = 0.5 * static_cast<double>(n - 1);
  const auto position = [&](double bearing) {
    return NormalizeAngle(bearing - angle_min - middle * increment) / increment + middle;
  };
  const double approximate = position(ApproximateAtan2(q.y(), q.x()));
  const double from_half_step = std::abs(approximate - std::floor(approximate) - 0.5);
  if (from_half_step > kApproximateAtan2Bound / increment + 1e-9) return std::round(approximate);
  return std::round(position(std::atan2(q.y(), q.x())));
}

}  // namespace scanloc
