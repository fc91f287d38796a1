#include "carmen_messages.hpp"

#include <cmath>

namespace scanloc::carmen {
namespace {

// Fields of a FLASER message besides its n ranges: the tag, n, then x y theta odom_x odom_y
// odom_theta ipc_timestamp hostname logger_timestamp.
constexpr std::size_t kFlaserFixedFields = 11;
// Fields of a RAWLASER1 message besides its ranges and remissions: the tag, laser_type start_angle
// fov angular_resolution max_range accuracy remission_mode, num_readings, num_remissions,
// ipc_timestamp hostname logger_timestamp.
constexpr std::size_t kRawLaserFixedFields = 13;
// Index of num_readings in ROBOTLASER1 and RAWLASER1 messages.
constexpr std::size_t kLaserCountField = 8;
// The fields of an ODOM message: the tag, x y theta tv rv accel ipc_timestamp hostname
// logger_timestamp.
constexpr std::size_t kOdomFields = 10;
// PARAM name value hostname timestamp, and PARAM name value ipc_timestamp hostname
// logger_timestamp.
constexpr std::size_t kShortParamFields = 5;
constexpr std::size_t kFullParamFields = 6;

// FLASER scans cover half a revolution around the heading.
constexpr double kFlaserFieldOfViewRad = M_PI;
// Slack for a scan whose beams span exactly one revolution.
constexpr double kRevolutionSlackRad = 1e-6;

constexpr char kRobotFrontlaserOffset[] = "robot_frontlaser_offset";

// Names shared by every message, built once rather than per field.
const std::string kRangeWhat = "range in metres";
const std::string kRemissionWhat = "remission value";
const std::string kCoordinateWhat = "coordinate in metres";
const std::string kAngleWhat = "angle in radians";
const std::string kVelocityWhat = "velocity";
const std::string kValueWhat = "number";
const std::string kTimestampWhat = "timestamp in seconds";

// FLASER's bearing step. The Freiburg logs store 180 or 360 beams at π/n (the last beam one step
// short of +90°) and 181 or 361 beams at π/(n−1) (the last beam at +90°). Other counts follow the
// same parity rule: even n as π/n, odd n as π/(n−1).
double FlaserIncrementRad(std::size_t beam_count) {
  return beam_count % 2 == 0 ? kFlaserFieldOfViewRad / static_cast<double>(beam_count)
                             : kFlaserFieldOfViewRad / static_cast<double>(beam_count - 1);
}

Pose2D ParsePose(const MessageFields& message, std::size_t first) {
  return Pose2D(message.Finite(first + 0, kCoordinateWhat),
                message.Finite(first + 1, kCoordinateWhat), message.Finite(first + 2, kAngleWhat))
      .Normalized();
}

// The bearing step of a ROBOTLASER1 or RAWLASER1: its angular_resolution, or when that is not
// given (0) its fov over the n − 1 steps between n beams.
double LaserIncrementRad(const MessageFields& message, std::size_t n) {
  const double fov_rad = message.Finite(3, kAngleWhat);
  double resolution_rad = message.Finite(4, kAngleWhat);
  if (resolution_rad == 0.0 && fov_rad > 0.0 && n > 1)
    resolution_rad = fov_rad / static_cast<double>(n - 1);
  if (!(resolution_rad > 0.0) ||
      resolution_rad * static_cast<double>(n) > 2.0 * M_PI + kRevolutionSlackRad)
    message.Fail(
        "expected a positive angular_resolution (or fov) with the beams spanning at most one "
        "revolution, got " +
        std::to_string(resolution_rad) + " rad for " + std::to_string(n) + " beams");
  return resolution_rad;
}

// The laser configuration, ranges and remissions shared by ROBOTLASER1 and RAWLASER1 (`fixed`
// fields besides ranges and remissions); returns the index of the first field after them.
std::size_t ParseLaserScan(const MessageFields& message, const std::string& tag, std::size_t fixed,
                           std::optional<double> no_return_m, LaserScan& scan) {
  if (message.size() <= kLaserCountField + 1)
    message.Fail(tag + " needs at least " + std::to_string(fixed) + " fields, got " +
                 std::to_string(message.size()));
  const std::size_t n = message.Beams(kLaserCountField, tag + " num_readings", 1);
  const std::size_t first_range = kLaserCountField + 1;
  if (first_range + n >= message.size())
    message.Fail(tag + " with num_readings = " + std::to_string(n) + " needs at least " +
                 std::to_string(n + fixed) + " fields, got " + std::to_string(message.size()));
  const std::size_t m = message.Beams(first_range + n, tag + " num_remissions", 0);
  message.ExpectSize(n + m + fixed, tag + " with num_readings = " + std::to_string(n) +
                                        " and num_remissions = " + std::to_string(m));

  message.Finite(1, kValueWhat);  // laser_type
  const double start_angle_rad = message.Finite(2, kAngleWhat);
  const double increment_rad = LaserIncrementRad(message, n);
  const double max_range_m = message.Finite(5, kRangeWhat);
  message.Finite(6, kValueWhat);  // accuracy
  message.Finite(7, kValueWhat);  // remission_mode
  if (!(max_range_m > 0.0)) message.Fail("expected a positive max_range");

  scan.ranges_m.resize(n);
  for (std::size_t i = 0; i < n; ++i) scan.ranges_m[i] = message.Any(first_range + i, kRangeWhat);
  // Remissions map onto beams only when there is one per beam.
  scan.reflectance.resize(m == n ? n : 0);
  for (std::size_t i = 0; i < m; ++i) {
    const double remission = message.Any(first_range + n + 1 + i, kRemissionWhat);
    if (m == n) scan.reflectance[i] = remission;
  }
  scan.layout = ScanLayout{};
  scan.layout.beam_count = n;
  scan.layout.angle_min_rad = start_angle_rad;
  scan.layout.angle_increment_rad = increment_rad;
  scan.layout.range_min_m = 0.0;
  scan.layout.range_max_m = no_return_m ? std::min(max_range_m, *no_return_m) : max_range_m;
  return first_range + n + 1 + m;
}

}  // namespace

std::size_t MessageFields::Count(std::size_t i, const std::string& what, long minimum) const {
  const long value = ParseInteger(fields_[i], file_, line_, what);
  if (value < minimum)
    Fail("expected " + what + " >= " + std::to_string(minimum) + ", got " + fields_[i]);
  return static_cast<std::size_t>(value);
}

std::size_t MessageFields::Beams(std::size_t i, const std::string& what, long minimum) const {
  const std::size_t value = Count(i, what, minimum);
  if (value > kMaxBeamsPerScan)
    Fail("expected " + what + " <= " + std::to_string(kMaxBeamsPerScan) +
         " (kMaxBeamsPerScan), got " + fields_[i]);
  return value;
}

void MessageFields::ExpectSize(std::size_t expected, const std::string& message) const {
  if (fields_.size() != expected)
    Fail(message + " needs " + std::to_string(expected) + " fields, got " +
         std::to_string(fields_.size()));
}

std::optional<LaserMessage> LaserMessageOf(const std::string& tag) {
  if (tag == "ROBOTLASER1") return LaserMessage::kRobotLaser1;
  if (tag == "FLASER") return LaserMessage::kFlaser;
  if (tag == "RAWLASER1") return LaserMessage::kRawLaser1;
  return std::nullopt;
}

void ParseFlaser(const MessageFields& message, double range_max_m, CarmenRecord& record) {
  if (message.size() < 2) message.Fail("FLASER needs a beam count n");
  const std::size_t n = message.Beams(1, "FLASER beam count n", 2);
  message.ExpectSize(n + kFlaserFixedFields, "FLASER with n = " + std::to_string(n));

  LaserScan& scan = record.scan;
  scan.ranges_m.resize(n);
  for (std::size_t i = 0; i < n; ++i) scan.ranges_m[i] = message.Any(2 + i, kRangeWhat);
  scan.reflectance.clear();
  scan.layout = ScanLayout{};
  scan.layout.beam_count = n;
  scan.layout.angle_min_rad = -kFlaserFieldOfViewRad / 2.0;
  scan.layout.angle_increment_rad = FlaserIncrementRad(n);
  scan.layout.range_min_m = 0.0;
  scan.layout.range_max_m = range_max_m;

  const std::size_t pose = 2 + n;  // x y theta, then odom_x odom_y odom_theta
  ParsePose(message, pose);
  record.odometry = ParsePose(message, pose + 3);
  record.has_odometry = true;
  record.timestamp_s = message.Finite(pose + 6, kTimestampWhat);
  message.Finite(pose + 8, kTimestampWhat);  // logger_timestamp, after the hostname
  record.velocity_mps.reset();
  record.kind = CarmenRecord::Kind::kLaser;
}

void ParseRobotLaser(const MessageFields& message, std::optional<double> no_return_m,
                     CarmenRecord& record) {
  const std::size_t pose =  // laser pose, then robot pose
      ParseLaserScan(message, "ROBOTLASER1", kRobotLaserFixedFields, no_return_m, record.scan);
  ParsePose(message, pose);
  record.odometry = ParsePose(message, pose + 3);
  record.has_odometry = true;
  record.velocity_mps = message.Finite(pose + 6, kValueWhat);                 // tv
  for (std::size_t i = 7; i < 11; ++i) message.Finite(pose + i, kValueWhat);  // rv .. turn_axis
  record.timestamp_s = message.Finite(pose + 11, kTimestampWhat);
  message.Finite(pose + 13, kTimestampWhat);  // logger_timestamp, after the hostname
  record.kind = CarmenRecord::Kind::kLaser;
}

void ParseRawLaser(const MessageFields& message, std::optional<double> no_return_m,
                   CarmenRecord& record) {
  const std::size_t time =
      ParseLaserScan(message, "RAWLASER1", kRawLaserFixedFields, no_return_m, record.scan);
  record.has_odometry = false;
  record.velocity_mps.reset();
  record.timestamp_s = message.Finite(time, kTimestampWhat);
  message.Finite(time + 2, kTimestampWhat);  // logger_timestamp, after the hostname
  record.kind = CarmenRecord::Kind::kLaser;
}

void ParseOdometry(const MessageFields& message, CarmenRecord& record) {
  message.ExpectSize(kOdomFields, "ODOM");
  record.odometry = ParsePose(message, 1);
  record.has_odometry = true;
  record.velocity_mps = message.Finite(4, kVelocityWhat);                // tv
  for (std::size_t i = 5; i < 7; ++i) message.Finite(i, kVelocityWhat);  // rv accel
  record.timestamp_s = message.Finite(7, kTimestampWhat);
  message.Finite(9, kTimestampWhat);  // logger_timestamp, after the hostname
  record.kind = CarmenRecord::Kind::kOdometry;
  // Cleared rather than reassigned: the buffers are reused by the next scan.
  record.scan.ranges_m.clear();
  record.scan.reflectance.clear();
  record.scan.layout = ScanLayout{};
  record.scan.timestamp_s = 0.0;
}

std::optional<double> ParseLaserOffsetParam(const MessageFields& message) {
  // Other parameters may hold values with spaces; only the laser offset is checked.
  if (message.size() < 2 || message[1] != kRobotFrontlaserOffset) return std::nullopt;
  if (message.size() == kShortParamFields) {
    message.Finite(4, kTimestampWhat);
  } else if (message.size() == kFullParamFields) {
    message.Finite(3, kTimestampWhat);  // ipc_timestamp
    message.Finite(5, kTimestampWhat);  // logger_timestamp, after the hostname
  } else {
    message.Fail(std::string("PARAM ") + kRobotFrontlaserOffset + " needs " +
                 std::to_string(kShortParamFields) + " fields (PARAM name value hostname " +
                 "timestamp) or " + std::to_string(kFullParamFields) +
                 " (PARAM name value ipc_timestamp hostname logger_timestamp), got " +
                 std::to_string(message.size()));
  }
  return message.Finite(2, kCoordinateWhat);
}

}  // namespace scanloc::carmen
