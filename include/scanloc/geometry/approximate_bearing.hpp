#pragma once
// A bearing cheaper than std::atan2, within a stated bound of it: for culls that must be exact,
// which widen their interval by more than the bound and ask std::atan2 only when the cull fails.

#include <cmath>

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

}  // namespace scanloc
