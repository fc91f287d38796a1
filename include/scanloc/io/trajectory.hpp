#pragma once
// Timestamped planar trajectories on disk: the TUM format that evaluation tools read, and the
// benchmark's corrected poses.

#include <cstddef>
#include <string>
#include <vector>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct StampedPose {
  double timestamp_s = 0.0;
  Pose2D pose;  // T_world_robot
};

// Watches a stream of timestamps for ones that do not increase: each timestamp not after its
// predecessor (gone backwards or repeated) is counted. Readers keep going; commands warn.
class TimestampOrder {
 public:
  void Add(double timestamp_s) {
    if (count_ > 0 && !(timestamp_s > last_s_)) ++not_increasing_;
    if (timestamp_s == 0.0) ++zero_;
    last_s_ = timestamp_s;
    ++count_;
  }
  std::size_t count() const { return count_; }                    // timestamps seen
  std::size_t not_increasing() const { return not_increasing_; }  // backwards or repeated
  std::size_t zero() const { return zero_; }                      // exactly 0

 private:
  double last_s_ = 0.0;
  std::size_t count_ = 0;
  std::size_t not_increasing_ = 0;
  std::size_t zero_ = 0;
};

// The poses, in file order, whose timestamp is not after the previous pose's.
std::size_t CountNonIncreasingTimestamps(const std::vector<StampedPose>& poses);

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

// Reads reference poses in either format, told apart by the first data line: 4 fields are
// corrected poses, 8 a TUM trajectory; every line must then have as many. Same errors.
std::vector<StampedPose> ReadReferencePoses(const std::string& path);

}  // namespace scanloc
