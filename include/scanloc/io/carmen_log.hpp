#pragma once
// A streaming reader of old-style CARMEN logs (plain or gzip-compressed): laser scans and odometry,
// one message at a time, so that a long log never sits in memory whole.

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct CarmenOptions {
  // FLASER readings at or beyond this are no-return values (81.83 in Intel, 50.00 in ACES, 81.91 in
  // Fr079) and become invalid through the layout's range_max_m. Metres, > 0. ROBOTLASER1 and
  // RAWLASER1 messages carry their own maximum range and use it instead.
  double max_range_m = 50.0;
  // The log's no-return value set by hand: readings at or beyond it carry no echo, in every laser
  // message (with max_range_m or the message's max_range, the lower one stands). Metres, > 0.
  // Unset: recognised from the log when detect_no_return is on.
  std::optional<double> no_return_m;
  // Recognise the log's own saturation code (Örebro's 32.767 m) from its first scans
  // (RecogniseSaturation, carmen_saturation.hpp); ignored when no_return_m is set.
  bool detect_no_return = true;
  // The laser's distance ahead of the robot's base along its heading; overrides the log's
  // PARAM robot_frontlaser_offset when set. Metres.
  std::optional<double> laser_offset_m;
  // For sequences read scan by scan (CarmenIterationSource): repair odometry increments, message
  // by message, that move forward while the velocity logged over them is negative
  // (OdometryReversalRepair).
  bool repair_reversed_odometry = true;
  // Throws std::invalid_argument for a non-positive or non-finite range or no-return value, or a
  // non-finite offset.
  void Validate() const;
};

struct CarmenRecord {
  enum class Kind { kLaser, kOdometry };
  Kind kind = Kind::kOdometry;
  double timestamp_s = 0.0;  // the message's ipc_timestamp
  LaserScan scan;            // kLaser only (empty otherwise); scan.timestamp_s = timestamp_s
  Pose2D odometry;           // T_odom_robot: ODOM's x y theta, FLASER's odom_x odom_y odom_theta,
                             // ROBOTLASER1's robot pose, for RAWLASER1 the latest ODOM before it
  bool has_odometry = true;  // false for a RAWLASER1 with no ODOM before it in the log
  std::size_t line = 0;      // 1-based line of the message in the log
  // ODOM's and ROBOTLASER1's translational velocity tv (m/s, negative when reversing); FLASER
  // carries none.
  std::optional<double> velocity_mps;
};

// Reads laser messages (FLASER, ROBOTLASER1, RAWLASER1), ODOM and PARAM robot_frontlaser_offset in
// file order, skipping comments, blank lines and other message types (counted by type in
// skipped_messages()).
// - FLASER's n beams span 180° around the heading from -90°, with a step of π/n for even n (180,
//   360) and π/(n−1) for odd n (181, 361), the convention of the Freiburg benchmark logs.
// - ROBOTLASER1 and RAWLASER1 place beam i at start_angle + i·angular_resolution, from the message
//   (fov / (n − 1) when the resolution is not positive). RAWLASER1 has no pose: it takes the
//   odometry of the latest ODOM before it in the file (none before the first ODOM).
// - A log carrying several laser kinds for the same scans is read through one of them: the first
//   of ROBOTLASER1, FLASER, RAWLASER1 met in the log's first lines (kPreviewLines), else the first
//   laser message met; the others are skipped and counted. RAWLASER2..4 (other lasers) are skipped.
// - PARAM robot_frontlaser_offset in either form (name value hostname timestamp, or name value
//   ipc_timestamp hostname logger_timestamp); set twice, the later value stands until the first
//   scan; a different value after it is ignored (the mounting stays the one the scans were read
//   with) and counted in ignored_laser_offsets().
// - The no-return value: options.no_return_m, else the log's saturation code recognised over its
//   first kPreviewScans scans (the file is read ahead once, then reopened: the reader still
//   streams), else max_range_m alone.
// A malformed message throws ParseError naming file and line; the reader then continues after that
// line. So do a line over kMaxLineBytes, a scan of more than kMaxBeamsPerScan beams and an odometry
// beyond ±kMaxCoordinateM.
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

  // The fraction of the file read so far, in [0, 1] (0 when the size is unknown).
  double Progress() const;
  // T_robot_laser = (D, 0, 0) from PARAM robot_frontlaser_offset D (0 when absent), or the option's
  // override; final once a laser record was returned.
  LaserMounting mounting() const;
  // Lines read so far.
  std::size_t lines_read() const;
  // The saturation code recognised in the log's first scans; nullopt when none was, or when
  // detection is off or options.no_return_m is set.
  std::optional<double> recognised_no_return_m() const;
  // FLASER's range limit in force: max_range_m, lowered to options.no_return_m or the recognised
  // value. Metres.
  double no_return_m() const;
  // Messages skipped so far, by type (unknown types, and laser kinds other than the one read).
  const std::map<std::string, std::size_t>& skipped_messages() const;
  // PARAM robot_frontlaser_offset lines after the first scan that would have changed the mounting.
  std::size_t ignored_laser_offsets() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The index-th (0-based) laser message of the log; throws std::runtime_error when it has fewer.
LaserScan ReadCarmenScan(const std::string& path, std::size_t index, CarmenOptions options = {});

}  // namespace scanloc
