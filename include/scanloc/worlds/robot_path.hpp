#pragma once
// A robot driven step by step through waypoints, one iteration per step (as the chapter's robot
// moved between acquisitions), and the drifting odometry it would report.

#include <Eigen/Core>
#include <random>
#include <vector>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct RobotPathOptions {
  double step_m = 0.2;          // distance driven between two iterations (equal steps per leg)
  double turn_step_rad = 0.35;  // heading change between two iterations when turning on the spot
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// The true postures T_world_robot, one per iteration: `start` first; then for each waypoint, turns
// on the spot towards it in equal steps of at most turn_step_rad, and drives straight to it in
// equal steps of at most step_m. Waypoints closer than 1 mm to the previous position are skipped.
std::vector<Pose2D> FollowWaypoints(const Pose2D& start,
                                    const std::vector<Eigen::Vector2d>& waypoints,
                                    const RobotPathOptions& options);

// How far the odometry strays from the true motion between two iterations.
struct OdometryNoiseOptions {
  double scale_error = 0.02;                // systematic: distances over-reported by this fraction
  double translation_sigma_per_m = 0.01;    // random error along and across, σ per metre driven
  double heading_sigma_per_m = 0.005;       // heading error σ per metre driven, rad/m
  double heading_sigma_per_rad = 0.02;      // heading error σ per radian turned
  double heading_sigma_per_step_rad = 0.0;  // heading error σ at every step, rad
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// The odometry T_odom_robot at each true posture: the true increments with noise drawn from `rng`,
// integrated from the identity.
std::vector<Pose2D> SimulateOdometry(const std::vector<Pose2D>& truth,
                                     const OdometryNoiseOptions& options, std::mt19937& rng);

}  // namespace scanloc
