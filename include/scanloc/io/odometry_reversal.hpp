#pragma once
// Some logs' odometry poses never move backward: the robot reverses, ODOM reports a negative
// translational velocity, and the pose still advances along the heading (Fr079: 328 of its 7,314
// ODOM increments). A session that trusts such a pose predicts 0.1 m ahead where the robot moved
// 0.1 m back. This repairs the odometry of each scan from the velocities logged since the scan
// before it.

#include <cstddef>
#include <optional>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

class OdometryReversalRepair {
 public:
  // Below this (m/s) a logged velocity says the robot is reversing.
  static constexpr double kReversingMps = 0.01;

  // A translational velocity (ODOM's or ROBOTLASER1's tv) logged since the previous scan.
  void AddVelocity(double tv_mps);

  // The odometry to use for the next scan, from the log's. When every velocity logged since the
  // previous scan says the robot reversed and the log's increment moves forward, the increment's
  // translation is reversed (its rotation is kept); later scans follow on from the repaired pose.
  // Until the first repair the log's pose is returned unchanged, bit for bit.
  Pose2D Repair(const Pose2D& logged);

  // How many increments were reversed so far.
  std::size_t repaired() const { return repaired_; }

 private:
  std::optional<Pose2D> logged_previous_;
  Pose2D repaired_previous_;
  std::optional<Pose2D> offset_;  // repaired = offset · logged, once a repair was made
  double max_velocity_mps_ = 0.0;
  std::size_t velocities_ = 0;
  std::size_t repaired_ = 0;
};

}  // namespace scanloc
