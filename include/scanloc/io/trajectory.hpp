#pragma once
// Timestamped planar trajectories on disk: the TUM format that evaluation tools read, and the
// benchmark's corrected poses.

#include <string>
#include <vector>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct StampedPose {
  double timestamp_s = 0.0;
  Pose2D pose;  // T_world_robot
};

// Writes one `t x y z qx qy qz qw` line per pose (TUM format; z = 0, a yaw-only quaternion) with
// microsecond timestamps (the logs' resolution) and micrometre positions, atomically (see
// WriteFileAtomically). Throws std::invalid_argument for a non-finite timestamp or pose,
// std::runtime_error when writing fails.
void WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses);

// Reads a TUM trajectory in file order, keeping x, y and the quaternion's heading (yaw); `#` lines
// are comments. Throws ParseError naming file and line for a malformed line, std::runtime_error
// when the file cannot be opened.
std::vector<StampedPose> ReadTumTrajectory(const std::string& path);

// Reads `timestamp x y theta` lines (the benchmark's *.corrected-poses.txt) in file order, with the
// same errors as ReadTumTrajectory.
std::vector<StampedPose> ReadCorrectedPoses(const std::string& path);

}  // namespace scanloc
