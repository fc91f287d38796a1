#include "scanloc/worlds/environment_simulation.hpp"

#include <cmath>
#include <random>

namespace scanloc {
namespace {

// Rounded to 1/per_unit; dividing by the exact integer gives the double nearest the decimal, which
// the JSON writer then prints in its few digits.
double RoundTo(double value, double per_unit) {
  return std::round(value * per_unit) / per_unit;
}

Pose2D Rounded(const Pose2D& pose) {
  return {RoundTo(pose.x_m, 1e4), RoundTo(pose.y_m, 1e4), RoundTo(pose.yaw_rad, 1e6)};
}

}  // namespace

std::vector<SimulatedIteration> SimulateEnvironment(const Environment& environment, unsigned seed,
                                                    std::size_t max_iterations) {
  environment.laser.Validate();
  std::vector<Pose2D> truth =
      FollowWaypoints(environment.start, environment.waypoints, environment.path);
  if (max_iterations > 0 && truth.size() > max_iterations) truth.resize(max_iterations);
  for (Pose2D& pose : truth) pose = Rounded(pose);
  // Separate streams, so that the odometry stays the same when the laser model changes.
  std::mt19937 odometry_rng(seed), laser_rng(seed + 0x9e3779b9u);
  const std::vector<Pose2D> odometry = SimulateOdometry(truth, environment.odometry, odometry_rng);
  const LineMap world = environment.world.Map();

  std::vector<SimulatedIteration> iterations(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    SimulatedIteration& it = iterations[i];
    it.timestamp_s = i * environment.scan_period_s;
    it.T_world_robot = truth[i];
    it.T_odom_robot = Rounded(odometry[i]);
    it.scan = SimulateLaser(world, environment.mounting.LaserPose(truth[i]), environment.laser,
                            laser_rng);
    it.scan.timestamp_s = it.timestamp_s;
    for (double& range : it.scan.ranges_m) {
      if (range < 0.0) continue;
      range = RoundTo(range, 1e3);
      if (!IsValidRange(range, it.scan.layout)) range = -1.0;
    }
  }
  return iterations;
}

}  // namespace scanloc
