#include "scanloc/worlds/robot_path.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace scanloc {
namespace {

void Require(bool ok, const char* type, const char* what) {
  if (!ok) throw std::invalid_argument(std::string(type) + ": " + what);
}

// Equal steps covering `total` with none longer than `max_step` (at least one when total > 0).
int StepCount(double total, double max_step) {
  return static_cast<int>(std::ceil(std::abs(total) / max_step - 1e-9));
}

}  // namespace

void RobotPathOptions::Validate() const {
  Require(std::isfinite(step_m) && step_m > 0.0, "RobotPathOptions", "step_m must be positive");
  Require(std::isfinite(turn_step_rad) && turn_step_rad > 0.0 && turn_step_rad <= M_PI,
          "RobotPathOptions", "turn_step_rad must be in (0, π]");
}

void OdometryNoiseOptions::Validate() const {
  for (const double v : {scale_error, translation_sigma_per_m, heading_sigma_per_m,
                         heading_sigma_per_rad, heading_sigma_per_step_rad})
    Require(std::isfinite(v), "OdometryNoiseOptions", "every option must be finite");
  Require(scale_error > -1.0, "OdometryNoiseOptions", "scale_error must be > -1");
  Require(translation_sigma_per_m >= 0.0 && heading_sigma_per_m >= 0.0 &&
              heading_sigma_per_rad >= 0.0 && heading_sigma_per_step_rad >= 0.0,
          "OdometryNoiseOptions", "σ must be >= 0");
}

std::vector<Pose2D> FollowWaypoints(const Pose2D& start,
                                    const std::vector<Eigen::Vector2d>& waypoints,
                                    const RobotPathOptions& options) {
  options.Validate();
  std::vector<Pose2D> path{start.Normalized()};
  for (const Eigen::Vector2d& goal : waypoints) {
    if (!goal.allFinite()) throw std::invalid_argument("FollowWaypoints: waypoint not finite");
    const Pose2D from = path.back();
    const Eigen::Vector2d leg = goal - from.Translation();
    const double length = leg.norm();
    if (length < 1e-3) continue;
    const double turn = NormalizeAngle(std::atan2(leg.y(), leg.x()) - from.yaw_rad);
    const int turns = StepCount(turn, options.turn_step_rad);
    for (int k = 1; k <= turns; ++k)
      path.push_back(Pose2D{from.x_m, from.y_m, from.yaw_rad + turn * k / turns}.Normalized());
    const double heading = path.back().yaw_rad;
    const int steps = StepCount(length, options.step_m);
    for (int k = 1; k <= steps; ++k) {
      const Eigen::Vector2d p = from.Translation() + leg * (static_cast<double>(k) / steps);
      path.push_back({p.x(), p.y(), heading});
    }
  }
  return path;
}

std::vector<Pose2D> SimulateOdometry(const std::vector<Pose2D>& truth,
                                     const OdometryNoiseOptions& options, std::mt19937& rng) {
  options.Validate();
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<Pose2D> odometry;
  odometry.reserve(truth.size());
  Pose2D T_odom_robot;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) {
      const Pose2D step = Between(truth[i - 1], truth[i]);
      const double distance = std::hypot(step.x_m, step.y_m);
      // Draw all three every step so that one option does not shift the others' draws.
      const double along = unit(rng), across = unit(rng), heading = unit(rng);
      const double sigma_m = options.translation_sigma_per_m * distance;
      const double sigma_rad = options.heading_sigma_per_m * distance +
                               options.heading_sigma_per_rad * std::abs(step.yaw_rad) +
                               options.heading_sigma_per_step_rad;
      const double scale = 1.0 + options.scale_error;
      const double direction = distance > 0.0 ? std::atan2(step.y_m, step.x_m) : 0.0;
      const double forward = distance * scale + sigma_m * along, sideways = sigma_m * across;
      const Pose2D measured{forward * std::cos(direction) - sideways * std::sin(direction),
                            forward * std::sin(direction) + sideways * std::cos(direction),
                            step.yaw_rad + sigma_rad * heading};
      T_odom_robot = (T_odom_robot * measured).Normalized();
    }
    odometry.push_back(T_odom_robot);
  }
  return odometry;
}

}  // namespace scanloc
