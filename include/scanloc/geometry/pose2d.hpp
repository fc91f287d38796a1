#pragma once
// A planar rigid transform (x, y, θ): the posture of a frame in another frame.

#include <Eigen/Core>
#include <cmath>
#include <iosfwd>

namespace scanloc {

// NormalizeAngle for any input (std::remainder); NormalizeAngle calls it outside ±9 rad.
double NormalizeAngleSlow(double angle_rad);

// Wraps an angle to (-π, π]. Inline, with the common cases first: simulated scans wrap every map
// point's bearing. Within one turn of the interval, x ∓ 2π is exact (Sterbenz), so the result
// equals std::remainder's bit for bit.
inline double NormalizeAngle(double angle_rad) {
  if (angle_rad > -M_PI && angle_rad <= M_PI) return angle_rad;
  if (angle_rad > M_PI && angle_rad < 9.0) return angle_rad - 2.0 * M_PI;
  if (angle_rad <= -M_PI && angle_rad > -9.0) return angle_rad + 2.0 * M_PI;
  return NormalizeAngleSlow(angle_rad);
}

// T_a_b: the pose of frame b expressed in frame a. Composition T_a_c = T_a_b * T_b_c.
struct Pose2D {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;

  Pose2D() = default;
  Pose2D(double x, double y, double yaw) : x_m(x), y_m(y), yaw_rad(yaw) {}

  Pose2D operator*(const Pose2D& other) const;
  Pose2D Inverse() const;
  // Maps a point given in this pose's frame into the parent frame.
  Eigen::Vector2d Transform(const Eigen::Vector2d& point) const;
  Eigen::Vector2d Translation() const { return {x_m, y_m}; }
  Pose2D Normalized() const { return {x_m, y_m, NormalizeAngle(yaw_rad)}; }
};

// A posture's cosine and sine taken once, to map many points into the parent frame: bit for bit
// Pose2D::Transform, which evaluates them per point.
struct PoseTransform {
  explicit PoseTransform(const Pose2D& pose)
      : x_m(pose.x_m), y_m(pose.y_m), c(std::cos(pose.yaw_rad)), s(std::sin(pose.yaw_rad)) {}
  Eigen::Vector2d operator()(const Eigen::Vector2d& point) const {
    return {x_m + c * point.x() - s * point.y(), y_m + s * point.x() + c * point.y()};
  }
  double x_m, y_m, c, s;
};

// Difference of two poses: a ⊖ b = b⁻¹ · a, the motion from b to a in b's frame.
Pose2D Between(const Pose2D& from, const Pose2D& to);

// The same posture to the bit: a posture carried over as it was, not one computed again.
inline bool SamePosture(const Pose2D& a, const Pose2D& b) {
  return a.x_m == b.x_m && a.y_m == b.y_m && a.yaw_rad == b.yaw_rad;
}

// The largest coordinate accepted from input: 1,000 km, beyond any map a planar laser builds.
// Larger values are data errors, and would overflow the point map's integer cell indices.
constexpr double kMaxCoordinateM = 1e6;
// True when x and y are finite and within ±kMaxCoordinateM and yaw is finite.
bool IsPlausiblePose(const Pose2D& pose);

std::ostream& operator<<(std::ostream& os, const Pose2D& pose);

}  // namespace scanloc
