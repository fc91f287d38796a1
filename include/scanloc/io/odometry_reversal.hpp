#pragma once
// Some logs' odometry poses never move backward: the robot reverses, ODOM reports a negative
// translational velocity, and the pose still advances along the heading (Fr079: 328 of its 7,314
// ODOM increments). A session that trusts such a pose predicts 0.1 m ahead where the robot moved
// 0.1 m back. This repairs the odometry message by message, so that a scan's odometry is right
// however many ODOM messages lie between it and the scan before (a log that keeps one scan a
// metre, with the robot reversing for part of it).

#include <cstddef>
#include <optional>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

class OdometryReversalRepair {
 public:
  // Below this (m/s) a logged velocity says the robot is reversing.
  static constexpr double kReversingMps = 0.01;

  // The odometry to use for the next message that carries one (ODOM, or a scan's), in file order,
  // from the log's pose and the translational velocity the message logged (ODOM's and
  // ROBOTLASER1's tv; none for FLASER). The increment from the message before is reversed (its
  // translation mirrored, its rotation kept) when it moves forward while the velocity says the
  // robot reverses: the message's own velocity, or without one the latest logged. Later messages
  // follow on from the repaired pose. Until the first repair the log's pose is returned
  // unchanged, bit for bit.
  Pose2D Follow(const Pose2D& logged, std::optional<double> velocity_mps);

  // How many increments were reversed so far.
  std::size_t repaired() const { return repaired_; }

 private:
  std::optional<Pose2D> logged_previous_;
  Pose2D repaired_previous_;
  std::optional<Pose2D> offset_;        // repaired = offset · logged, once a repair was made
  std::optional<double> velocity_mps_;  // the latest velocity logged
  std::size_t repaired_ = 0;
};

}  // namespace scanloc
