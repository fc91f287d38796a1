#pragma once
// Some logs' odometry poses never move backward: the robot reverses, ODOM reports a negative
// translational velocity, and the pose still advances along the heading (Fr079: 328 of its 7,314
// ODOM increments). A session that trusts such a pose predicts 0.1 m ahead where the robot moved
// 0.1 m back. This repairs the odometry of the scans. Where the scans' odometry lies in the ODOM
// messages' frame, each ODOM increment is judged by its own velocity, so that a scan's odometry is
// right however many ODOM messages lie between it and the scan before (a log that keeps one scan
// a metre, with the robot reversing for part of it). Elsewhere (no ODOM, or scans whose pose
// fields were not filled in) a scan's increment is judged by every velocity logged since the scan
// before.

#include <cstddef>
#include <optional>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

class OdometryReversalRepair {
 public:
  // Below this (m/s) a logged velocity says the robot is reversing.
  static constexpr double kReversingMps = 0.01;
  // A scan's odometry lies in the ODOM messages' frame when it is within this of the latest
  // ODOM's pose, beyond the distance the robot can have driven between the two messages.
  static constexpr double kSameFrameM = 0.1;

  // An ODOM message: its pose, translational velocity tv and timestamp.
  void AddOdometry(const Pose2D& logged, double tv_mps, double timestamp_s);

  // The odometry to use for a scan, from its logged pose, the velocity the scan message logged
  // (ROBOTLASER1's tv; none for FLASER) and its timestamp. In the ODOM messages' frame: the
  // correction the ODOM increments' repairs add up to, applied to the scan's pose. Otherwise its
  // increment from the scan before, reversed (translation mirrored, rotation kept) when it moves
  // forward while every velocity logged since that scan says the robot reversed. Until the first
  // repair the log's pose is returned unchanged, bit for bit.
  Pose2D Repair(const Pose2D& logged, std::optional<double> velocity_mps, double timestamp_s);

  // How many increments (ODOM's or the scans') were reversed so far.
  std::size_t repaired() const { return repaired_; }

 private:
  // A sequence of poses in one frame and the correction its reversed increments add up to.
  struct Chain {
    std::optional<Pose2D> logged_previous;
    Pose2D repaired_previous;
    std::optional<Pose2D> offset;  // repaired = offset · logged, once a repair was made
    Pose2D Corrected(const Pose2D& logged) const;
    // The next pose; its increment is reversed when `reversing` and it moves forward.
    Pose2D Follow(const Pose2D& logged, bool reversing, std::size_t& repaired);
  };

  bool InOdometryFrame(const Pose2D& logged, double timestamp_s) const;
  // A velocity logged since the previous scan.
  void NoteVelocity(double tv_mps);

  Chain odometry_, scans_;
  std::optional<Pose2D> odometry_logged_;  // the latest ODOM's
  double odometry_velocity_mps_ = 0.0, odometry_timestamp_s_ = 0.0;
  double max_velocity_mps_ = 0.0;  // since the previous scan
  std::size_t velocities_ = 0;
  std::size_t repaired_ = 0;
};

}  // namespace scanloc
