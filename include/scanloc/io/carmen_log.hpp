#pragma once
// A streaming reader of old-style CARMEN logs (plain or gzip-compressed): laser scans and odometry,
// one message at a time, so that a long log never sits in memory whole.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct CarmenOptions {
  // FLASER readings at or beyond this are no-return values (81.83 in Intel, 50.00 in ACES, 81.91 in
  // Fr079) and become invalid through the layout's range_max_m. Metres, > 0. ROBOTLASER1 messages
  // carry their own maximum range and use it instead.
  double max_range_m = 50.0;
  // The laser's distance ahead of the robot's base along its heading; overrides the log's
  // PARAM robot_frontlaser_offset when set. Metres.
  std::optional<double> laser_offset_m;
  // For sequences read scan by scan (CarmenIterationSource): repair odometry increments that move
  // forward while every ODOM logged in between reports a negative velocity
  // (OdometryReversalRepair).
  bool repair_reversed_odometry = true;
  // Throws std::invalid_argument for a non-positive or non-finite range or a non-finite offset.
  void Validate() const;
};

struct CarmenRecord {
  enum class Kind { kLaser, kOdometry };
  Kind kind = Kind::kOdometry;
  double timestamp_s = 0.0;  // the message's ipc_timestamp
  LaserScan scan;            // kLaser only (empty otherwise); scan.timestamp_s = timestamp_s
  Pose2D odometry;           // T_odom_robot: ODOM's x y theta, FLASER's odom_x odom_y odom_theta,
                             // ROBOTLASER1's robot pose
  std::size_t line = 0;      // 1-based line of the message in the log
  // ODOM's and ROBOTLASER1's translational velocity tv (m/s, negative when reversing); FLASER
  // carries none.
  std::optional<double> velocity_mps;
};

// Reads FLASER, ROBOTLASER1, ODOM and PARAM robot_frontlaser_offset messages in file order,
// skipping comments, blank lines and other message types. FLASER's n beams span 180° around the
// heading from -90°, with a step of π/n for even n (180, 360) and π/(n−1) for odd n (181, 361), the
// convention of the Freiburg benchmark logs. A malformed message throws ParseError naming file and
// line; the reader then continues after that line. So do a line over kMaxLineBytes, a scan of more
// than kMaxBeamsPerScan beams and an odometry beyond ±kMaxCoordinateM.
class CarmenReader {
 public:
  // Throws std::runtime_error naming the path when the file cannot be opened.
  explicit CarmenReader(const std::string& path, CarmenOptions options = {});
  ~CarmenReader();
  CarmenReader(CarmenReader&&) noexcept;
  CarmenReader& operator=(CarmenReader&&) noexcept;
  CarmenReader(const CarmenReader&) = delete;
  CarmenReader& operator=(const CarmenReader&) = delete;

  // Fills `record` with the next laser or odometry message; false at the end of the log. After a
  // ParseError `record` is unspecified and the next call resumes at the following line.
  bool Next(CarmenRecord& record);

  // T_robot_laser = (D, 0, 0) from PARAM robot_frontlaser_offset D (0 when absent), or the option's
  // override. The PARAM precedes the first scan, so this is final once a laser record was returned.
  // The fraction of the file read so far, in [0, 1] (0 when the size is unknown).
  double Progress() const;
  LaserMounting mounting() const;
  // Lines read so far.
  std::size_t lines_read() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The index-th (0-based) laser message of the log; throws std::runtime_error when it has fewer.
LaserScan ReadCarmenScan(const std::string& path, std::size_t index, CarmenOptions options = {});

}  // namespace scanloc
