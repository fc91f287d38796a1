#include "scanloc/io/trajectory.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <ostream>
#include <stdexcept>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"

namespace scanloc {
namespace {

// t x y z qx qy qz qw
constexpr std::size_t kTumFields = 8;
// timestamp x y theta
constexpr std::size_t kCorrectedPoseFields = 4;
// A quaternion this close to zero has no heading.
constexpr double kMinQuaternionNorm = 1e-9;

// Calls `parse` with the fields of every non-blank, non-comment line of the file.
void ForEachDataLine(
    const std::string& path,
    const std::function<void(const std::vector<std::string>& fields, std::size_t line)>& parse) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string text;
  std::size_t line = 0;
  // Both formats have at most kTumFields fields: more are reported without being split.
  while (ReadBoundedLine(in, text, path, ++line)) {
    const std::vector<std::string> fields = SplitFields(text, kTumFields);
    if (!fields.empty()) parse(fields, line);
  }
  if (in.bad()) throw std::runtime_error("error while reading " + path);
}

// One `t x y z qx qy qz qw` line (TUM).
StampedPose TumPose(const std::vector<std::string>& fields, const std::string& path,
                    std::size_t line) {
  if (fields.size() != kTumFields)
    throw ParseError(
        path, line,
        "expected 8 fields 't x y z qx qy qz qw', got " + std::to_string(fields.size()));
  StampedPose stamped;
  stamped.timestamp_s = ParseFiniteDouble(fields[0], path, line, "timestamp in seconds");
  stamped.pose.x_m = ParseFiniteDouble(fields[1], path, line, "x in metres");
  stamped.pose.y_m = ParseFiniteDouble(fields[2], path, line, "y in metres");
  ParseFiniteDouble(fields[3], path, line, "z in metres");
  double qx = ParseFiniteDouble(fields[4], path, line, "quaternion qx");
  double qy = ParseFiniteDouble(fields[5], path, line, "quaternion qy");
  double qz = ParseFiniteDouble(fields[6], path, line, "quaternion qz");
  double qw = ParseFiniteDouble(fields[7], path, line, "quaternion qw");
  // Normalised first: components of 1e200 would overflow the products below to inf and NaN.
  const double norm = std::hypot(std::hypot(qx, qy), std::hypot(qz, qw));
  if (!(norm >= kMinQuaternionNorm) || !std::isfinite(norm))
    throw ParseError(path, line, "expected a non-zero quaternion");
  qx /= norm, qy /= norm, qz /= norm, qw /= norm;
  // The heading of the rotated x axis (ZYX yaw); exact for the yaw-only quaternions we write,
  // and unaffected by the quaternion's scale.
  stamped.pose.yaw_rad =
      std::atan2(2.0 * (qw * qz + qx * qy), qw * qw + qx * qx - qy * qy - qz * qz);
  return stamped;
}

// One `timestamp x y theta` line (the benchmark's *.corrected-poses.txt).
StampedPose CorrectedPose(const std::vector<std::string>& fields, const std::string& path,
                          std::size_t line) {
  if (fields.size() != kCorrectedPoseFields)
    throw ParseError(
        path, line,
        "expected 4 fields 'timestamp x y theta', got " + std::to_string(fields.size()));
  StampedPose stamped;
  stamped.timestamp_s = ParseFiniteDouble(fields[0], path, line, "timestamp in seconds");
  stamped.pose = Pose2D(ParseFiniteDouble(fields[1], path, line, "x in metres"),
                        ParseFiniteDouble(fields[2], path, line, "y in metres"),
                        ParseFiniteDouble(fields[3], path, line, "theta in radians"))
                     .Normalized();
  return stamped;
}

}  // namespace

void WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses) {
  for (const StampedPose& stamped : poses) {
    const Pose2D& pose = stamped.pose;
    if (!std::isfinite(stamped.timestamp_s) || !std::isfinite(pose.x_m) ||
        !std::isfinite(pose.y_m) || !std::isfinite(pose.yaw_rad))
      throw std::invalid_argument("WriteTumTrajectory: non-finite pose or timestamp for " + path);
  }
  WriteFileAtomically(path, [&poses](std::ostream& out) {
    out << "# timestamp x y z qx qy qz qw\n";
    char buffer[256];
    for (const StampedPose& stamped : poses) {
      const Pose2D& pose = stamped.pose;
      // A rotation by yaw about z: q = (0, 0, sin(yaw/2), cos(yaw/2)).
      const double half_yaw_rad = pose.yaw_rad / 2.0;
      std::snprintf(buffer, sizeof(buffer), "%.6f %.6f %.6f 0 0 0 %.9f %.9f\n", stamped.timestamp_s,
                    pose.x_m, pose.y_m, std::sin(half_yaw_rad), std::cos(half_yaw_rad));
      out << buffer;
    }
  });
}

std::vector<StampedPose> ReadTumTrajectory(const std::string& path) {
  std::vector<StampedPose> poses;
  ForEachDataLine(path, [&](const std::vector<std::string>& fields, std::size_t line) {
    poses.push_back(TumPose(fields, path, line));
  });
  return poses;
}

std::vector<StampedPose> ReadCorrectedPoses(const std::string& path) {
  std::vector<StampedPose> poses;
  ForEachDataLine(path, [&](const std::vector<std::string>& fields, std::size_t line) {
    poses.push_back(CorrectedPose(fields, path, line));
  });
  return poses;
}

std::vector<StampedPose> ReadReferencePoses(const std::string& path) {
  std::vector<StampedPose> poses;
  std::size_t format_fields = 0;  // the first data line's
  ForEachDataLine(path, [&](const std::vector<std::string>& fields, std::size_t line) {
    if (format_fields == 0) format_fields = fields.size();
    if (format_fields == kTumFields) {
      poses.push_back(TumPose(fields, path, line));
    } else if (format_fields == kCorrectedPoseFields) {
      poses.push_back(CorrectedPose(fields, path, line));
    } else {
      throw ParseError(path, line,
                       "expected 4 fields 'timestamp x y theta' or 8 fields 't x y z qx qy qz "
                       "qw', got " +
                           std::to_string(fields.size()));
    }
  });
  return poses;
}

std::size_t CountNonIncreasingTimestamps(const std::vector<StampedPose>& poses) {
  TimestampOrder order;
  for (const StampedPose& stamped : poses) order.Add(stamped.timestamp_s);
  return order.not_increasing();
}

}  // namespace scanloc
