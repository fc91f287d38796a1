#pragma once
// The CARMEN messages the reader understands, one parser each (private to src/io). Each parser
// fills a CarmenRecord from a message's fields or throws ParseError naming the file and line.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/carmen_log.hpp"

namespace scanloc::carmen {

// Fields of a ROBOTLASER1 message besides its ranges and remissions: the tag, laser_type
// start_angle fov angular_resolution max_range accuracy remission_mode, num_readings,
// num_remissions, laser pose (3), robot pose (3), tv rv forward_safety_dist side_safety_dist
// turn_axis, ipc_timestamp hostname logger_timestamp.
constexpr std::size_t kRobotLaserFixedFields = 24;
// The most fields a message may have: a ROBOTLASER1 at the beam cap with a remission per beam.
// A line with more is refused before a string is made of each field.
constexpr std::size_t kMaxMessageFields = 2 * kMaxBeamsPerScan + kRobotLaserFixedFields;

// The fields of one message with the file and line that errors must name.
class MessageFields {
 public:
  MessageFields(const std::vector<std::string>& fields, const std::string& file, std::size_t line)
      : fields_(fields), file_(file), line_(line) {}

  std::size_t size() const { return fields_.size(); }
  const std::string& operator[](std::size_t i) const { return fields_[i]; }
  double Finite(std::size_t i, const std::string& what) const {
    return ParseFiniteDouble(fields_[i], file_, line_, what);
  }
  // Ranges and remissions may be "nan" or "inf": such beams are simply invalid.
  double Any(std::size_t i, const std::string& what) const {
    return ParseDouble(fields_[i], file_, line_, what);
  }
  std::size_t Count(std::size_t i, const std::string& what, long minimum) const;
  // A count of beams: at least `minimum`, at most kMaxBeamsPerScan.
  std::size_t Beams(std::size_t i, const std::string& what, long minimum) const;
  void ExpectSize(std::size_t expected, const std::string& message) const;
  [[noreturn]] void Fail(const std::string& what) const { throw ParseError(file_, line_, what); }

 private:
  const std::vector<std::string>& fields_;
  const std::string& file_;
  std::size_t line_;
};

// The laser messages, in the order of preference when a log carries several kinds for the same
// scans: ROBOTLASER1 (its own layout and range limit, with the robot's odometry), FLASER (fixed
// 180° layout, with odometry), RAWLASER1 (its own layout, no pose).
enum class LaserMessage { kRobotLaser1, kFlaser, kRawLaser1 };
std::optional<LaserMessage> LaserMessageOf(const std::string& tag);

// FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp hostname logger_timestamp.
// Readings at or beyond range_max_m are no-return values.
void ParseFlaser(const MessageFields& message, double range_max_m, CarmenRecord& record);
// ROBOTLASER1 and RAWLASER1: the layout from the message; readings at or beyond the message's
// max_range, or no_return_m when lower, are no-return values. RAWLASER1 carries no pose: its
// record's odometry is left to the caller (has_odometry false).
void ParseRobotLaser(const MessageFields& message, std::optional<double> no_return_m,
                     CarmenRecord& record);
void ParseRawLaser(const MessageFields& message, std::optional<double> no_return_m,
                   CarmenRecord& record);
// ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp.
void ParseOdometry(const MessageFields& message, CarmenRecord& record);
// The value of a PARAM robot_frontlaser_offset, in either form (name value hostname timestamp, or
// name value ipc_timestamp hostname logger_timestamp); nullopt for any other parameter.
std::optional<double> ParseLaserOffsetParam(const MessageFields& message);

}  // namespace scanloc::carmen
