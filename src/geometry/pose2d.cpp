#include "scanloc/geometry/pose2d.hpp"

#include <ostream>

namespace scanloc {

double NormalizeAngleSlow(double angle_rad) {
  if (!std::isfinite(angle_rad)) return angle_rad;
  double a = std::remainder(angle_rad, 2.0 * M_PI);  // in [-π, π]
  if (a <= -M_PI) a += 2.0 * M_PI;
  return a;
}

Pose2D Pose2D::operator*(const Pose2D& other) const {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return {x_m + c * other.x_m - s * other.y_m, y_m + s * other.x_m + c * other.y_m,
          NormalizeAngle(yaw_rad + other.yaw_rad)};
}

Pose2D Pose2D::Inverse() const {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return {-c * x_m - s * y_m, s * x_m - c * y_m, NormalizeAngle(-yaw_rad)};
}

Eigen::Vector2d Pose2D::Transform(const Eigen::Vector2d& point) const {
  return PoseTransform(*this)(point);
}

Pose2D Between(const Pose2D& from, const Pose2D& to) {
  return from.Inverse() * to;
}

std::ostream& operator<<(std::ostream& os, const Pose2D& pose) {
  return os << "(" << pose.x_m << ", " << pose.y_m << ", " << pose.yaw_rad << ")";
}

bool IsPlausiblePose(const Pose2D& pose) {
  return std::abs(pose.x_m) <= kMaxCoordinateM && std::abs(pose.y_m) <= kMaxCoordinateM &&
         std::isfinite(pose.yaw_rad);
}

}  // namespace scanloc
