#include "scanloc/io/carmen_log.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"

namespace scanloc {
namespace {

// Fields of a FLASER message besides its n ranges: the tag, n, then x y theta odom_x odom_y
// odom_theta ipc_timestamp hostname logger_timestamp.
constexpr std::size_t kFlaserFixedFields = 11;
// The fields of an ODOM message: the tag, x y theta tv rv accel ipc_timestamp hostname
// logger_timestamp.
constexpr std::size_t kOdomFields = 10;
// PARAM name value hostname timestamp.
constexpr std::size_t kParamFields = 5;
// Fields of a ROBOTLASER1 message besides its ranges and remissions: the tag, laser_type
// start_angle fov angular_resolution max_range accuracy remission_mode, num_readings,
// num_remissions, laser pose (3), robot pose (3), tv rv forward_safety_dist side_safety_dist
// turn_axis, ipc_timestamp hostname logger_timestamp.
constexpr std::size_t kRobotLaserFixedFields = 24;
// Index of num_readings in a ROBOTLASER1 message.
constexpr std::size_t kRobotLaserCountField = 8;
// The most fields a message may have: a ROBOTLASER1 at the beam cap with a remission per beam.
// A line with more is refused before a string is made of each field.
constexpr std::size_t kMaxMessageFields = 2 * kMaxBeamsPerScan + kRobotLaserFixedFields;

// FLASER scans cover half a revolution around the heading.
constexpr double kFlaserFieldOfViewRad = M_PI;
// Slack for a scan whose beams span exactly one revolution.
constexpr double kRevolutionSlackRad = 1e-6;

// gzgets reads at most this much per call; longer lines are assembled from several calls.
constexpr int kReadChunkBytes = 64 * 1024;
// zlib's internal buffer: large enough that decompression is not the bottleneck.
constexpr unsigned kGzipBufferBytes = 256 * 1024;

constexpr char kRobotFrontlaserOffset[] = "robot_frontlaser_offset";

// FLASER's bearing step. The Freiburg logs store 180 or 360 beams at π/n (the last beam one step
// short of +90°) and 181 or 361 beams at π/(n−1) (the last beam at +90°). Other counts follow the
// same parity rule: even n as π/n, odd n as π/(n−1).
double FlaserIncrementRad(std::size_t beam_count) {
  return beam_count % 2 == 0 ? kFlaserFieldOfViewRad / static_cast<double>(beam_count)
                             : kFlaserFieldOfViewRad / static_cast<double>(beam_count - 1);
}

// The fields of one message with the file and line that errors must name.
class MessageFields {
 public:
  MessageFields(const std::vector<std::string>& fields, const std::string& file, std::size_t line)
      : fields_(fields), file_(file), line_(line) {}

  std::size_t size() const { return fields_.size(); }
  double Finite(std::size_t i, const std::string& what) const {
    return ParseFiniteDouble(fields_[i], file_, line_, what);
  }
  // Ranges and remissions may be "nan" or "inf": such beams are simply invalid.
  double Any(std::size_t i, const std::string& what) const {
    return ParseDouble(fields_[i], file_, line_, what);
  }
  std::size_t Count(std::size_t i, const std::string& what, long minimum) const {
    const long value = ParseInteger(fields_[i], file_, line_, what);
    if (value < minimum)
      Fail("expected " + what + " >= " + std::to_string(minimum) + ", got " + fields_[i]);
    return static_cast<std::size_t>(value);
  }
  // A count of beams: at least `minimum`, at most kMaxBeamsPerScan.
  std::size_t Beams(std::size_t i, const std::string& what, long minimum) const {
    const std::size_t value = Count(i, what, minimum);
    if (value > kMaxBeamsPerScan)
      Fail("expected " + what + " <= " + std::to_string(kMaxBeamsPerScan) +
           " (kMaxBeamsPerScan), got " + fields_[i]);
    return value;
  }
  void ExpectSize(std::size_t expected, const std::string& message) const {
    if (fields_.size() != expected)
      Fail(message + " needs " + std::to_string(expected) + " fields, got " +
           std::to_string(fields_.size()));
  }
  [[noreturn]] void Fail(const std::string& what) const { throw ParseError(file_, line_, what); }

 private:
  const std::vector<std::string>& fields_;
  const std::string& file_;
  std::size_t line_;
};

// Names shared by every message, built once rather than per field.
const std::string kRangeWhat = "range in metres";
const std::string kRemissionWhat = "remission value";
const std::string kCoordinateWhat = "coordinate in metres";
const std::string kAngleWhat = "angle in radians";
const std::string kVelocityWhat = "velocity";
const std::string kValueWhat = "number";
const std::string kTimestampWhat = "timestamp in seconds";

}  // namespace

void CarmenOptions::Validate() const {
  if (!(max_range_m > 0.0) || !std::isfinite(max_range_m))
    throw std::invalid_argument("CarmenOptions: max_range_m must be positive and finite, got " +
                                std::to_string(max_range_m));
  if (laser_offset_m && !std::isfinite(*laser_offset_m))
    throw std::invalid_argument("CarmenOptions: laser_offset_m must be finite");
}

struct CarmenReader::Impl {
  Impl(const std::string& log_path, CarmenOptions reader_options)
      : path(log_path), options(reader_options), chunk(kReadChunkBytes) {
    options.Validate();
    errno = 0;
    file = gzopen(path.c_str(), "rb");
    if (file == nullptr)
      throw std::runtime_error("cannot open CARMEN log " + path + ": " +
                               (errno != 0 ? std::strerror(errno) : "out of memory"));
    gzbuffer(file, kGzipBufferBytes);
    std::error_code error;
    file_bytes = std::filesystem::file_size(path, error);
    if (error) file_bytes = 0;
  }
  ~Impl() { gzclose(file); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  // Reads the next line (without its newline) into `text`; false at the end of the file. A line
  // longer than kMaxLineBytes throws; the next call resumes after it.
  bool ReadLine() {
    text.clear();
    if (broken) return false;  // a corrupt stream ends at its first error
    if (skipping_long_line) SkipRestOfLine();
    while (true) {
      if (gzgets(file, chunk.data(), kReadChunkBytes) == nullptr) {
        int status = Z_OK;
        const char* message = gzerror(file, &status);
        if (status != Z_OK) {
          broken = true;  // zlib cannot go on past it: a caller that resumes reaches the end
          throw ParseError(path, line + 1, std::string("cannot read: ") + message);
        }
        if (text.empty()) return false;
        break;  // a last line without a newline
      }
      text.append(chunk.data());
      const bool complete = !text.empty() && text.back() == '\n';
      if (text.size() - (complete ? 1 : 0) > kMaxLineBytes) {
        skipping_long_line = !complete;
        text.clear();
        ThrowLineTooLong(path, ++line, kMaxLineBytes);
      }
      if (complete) break;
    }
    ++line;
    return true;
  }

  // Reads on, a chunk at a time, to the end of the line that was too long.
  void SkipRestOfLine() {
    skipping_long_line = false;
    while (gzgets(file, chunk.data(), kReadChunkBytes) != nullptr) {
      const std::size_t length = std::strlen(chunk.data());
      if (length > 0 && chunk[length - 1] == '\n') return;
    }
  }

  bool Next(CarmenRecord& record) {
    while (ReadLine()) {
      fields = SplitFields(text, kMaxMessageFields);  // also drops `#` comments
      if (fields.empty()) continue;
      const MessageFields message(fields, path, line);
      if (fields.size() > kMaxMessageFields)
        message.Fail("more than " + std::to_string(kMaxMessageFields) +
                     " fields in one message: a scan has at most " +
                     std::to_string(kMaxBeamsPerScan) + " beams (kMaxBeamsPerScan)");
      const std::string& type = fields.front();
      if (type == "FLASER") {
        ParseFlaser(message, record);
      } else if (type == "ROBOTLASER1") {
        ParseRobotLaser(message, record);
      } else if (type == "ODOM") {
        ParseOdometry(message, record);
      } else {
        if (type == "PARAM") ParseParam(message);
        continue;  // other message types carry nothing we use
      }
      if (!IsPlausiblePose(record.odometry))
        message.Fail("odometry beyond ±" + std::to_string(static_cast<long>(kMaxCoordinateM)) +
                     " m, expected a planar posture in metres");
      record.line = line;
      if (record.kind == CarmenRecord::Kind::kLaser) {
        record.scan.timestamp_s = record.timestamp_s;
        seen_laser = true;
      }
      return true;
    }
    return false;
  }

  void ParseFlaser(const MessageFields& message, CarmenRecord& record) const {
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
    scan.layout.range_max_m = options.max_range_m;

    const std::size_t pose = 2 + n;  // x y theta, then odom_x odom_y odom_theta
    message.Finite(pose + 0, kCoordinateWhat);
    message.Finite(pose + 1, kCoordinateWhat);
    message.Finite(pose + 2, kAngleWhat);
    record.odometry =
        Pose2D(message.Finite(pose + 3, kCoordinateWhat), message.Finite(pose + 4, kCoordinateWhat),
               message.Finite(pose + 5, kAngleWhat))
            .Normalized();
    record.timestamp_s = message.Finite(pose + 6, kTimestampWhat);
    message.Finite(pose + 8, kTimestampWhat);  // logger_timestamp, after the hostname
    record.velocity_mps.reset();
    record.kind = CarmenRecord::Kind::kLaser;
  }

  void ParseRobotLaser(const MessageFields& message, CarmenRecord& record) const {
    if (message.size() <= kRobotLaserCountField + 1)
      message.Fail("ROBOTLASER1 needs at least " + std::to_string(kRobotLaserFixedFields) +
                   " fields, got " + std::to_string(message.size()));
    const std::size_t n = message.Beams(kRobotLaserCountField, "ROBOTLASER1 num_readings", 1);
    const std::size_t first_range = kRobotLaserCountField + 1;
    if (first_range + n >= message.size())
      message.Fail("ROBOTLASER1 with num_readings = " + std::to_string(n) + " needs at least " +
                   std::to_string(n + kRobotLaserFixedFields) + " fields, got " +
                   std::to_string(message.size()));
    const std::size_t m = message.Beams(first_range + n, "ROBOTLASER1 num_remissions", 0);
    message.ExpectSize(n + m + kRobotLaserFixedFields,
                       "ROBOTLASER1 with num_readings = " + std::to_string(n) +
                           " and num_remissions = " + std::to_string(m));

    message.Finite(1, kValueWhat);  // laser_type
    const double start_angle_rad = message.Finite(2, kAngleWhat);
    message.Finite(3, kAngleWhat);  // fov: implied by the resolution and the count
    const double resolution_rad = message.Finite(4, kAngleWhat);
    const double max_range_m = message.Finite(5, kRangeWhat);
    message.Finite(6, kValueWhat);  // accuracy
    message.Finite(7, kValueWhat);  // remission_mode
    if (!(resolution_rad > 0.0) ||
        resolution_rad * static_cast<double>(n) > 2.0 * M_PI + kRevolutionSlackRad)
      message.Fail(
          "expected a positive angular_resolution with the beams spanning at most one "
          "revolution, got " +
          std::to_string(resolution_rad) + " rad for " + std::to_string(n) + " beams");
    if (!(max_range_m > 0.0)) message.Fail("expected a positive max_range");

    LaserScan& scan = record.scan;
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
    scan.layout.angle_increment_rad = resolution_rad;
    scan.layout.range_min_m = 0.0;
    scan.layout.range_max_m = max_range_m;

    const std::size_t pose = first_range + n + 1 + m;  // laser pose, then robot pose
    for (std::size_t i = 0; i < 2; ++i) {
      message.Finite(pose + 3 * i + 0, kCoordinateWhat);
      message.Finite(pose + 3 * i + 1, kCoordinateWhat);
      message.Finite(pose + 3 * i + 2, kAngleWhat);
    }
    record.odometry =
        Pose2D(message.Finite(pose + 3, kCoordinateWhat), message.Finite(pose + 4, kCoordinateWhat),
               message.Finite(pose + 5, kAngleWhat))
            .Normalized();
    record.velocity_mps = message.Finite(pose + 6, kValueWhat);                 // tv
    for (std::size_t i = 7; i < 11; ++i) message.Finite(pose + i, kValueWhat);  // rv .. turn_axis
    record.timestamp_s = message.Finite(pose + 11, kTimestampWhat);
    message.Finite(pose + 13, kTimestampWhat);  // logger_timestamp, after the hostname
    record.kind = CarmenRecord::Kind::kLaser;
  }

  void ParseOdometry(const MessageFields& message, CarmenRecord& record) const {
    message.ExpectSize(kOdomFields, "ODOM");
    record.odometry = Pose2D(message.Finite(1, kCoordinateWhat), message.Finite(2, kCoordinateWhat),
                             message.Finite(3, kAngleWhat))
                          .Normalized();
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

  void ParseParam(const MessageFields& message) {
    // Other parameters may hold values with spaces; only the laser offset is checked.
    if (message.size() < 2 || fields[1] != kRobotFrontlaserOffset) return;
    message.ExpectSize(kParamFields, std::string("PARAM ") + kRobotFrontlaserOffset);
    const double offset_m = message.Finite(2, kCoordinateWhat);
    // Scans already returned were interpreted with the old mounting.
    if (seen_laser && offset_m != frontlaser_offset_m)
      message.Fail(std::string(kRobotFrontlaserOffset) + " must not change after the first scan");
    frontlaser_offset_m = offset_m;
  }

  std::string path;
  CarmenOptions options;
  gzFile file = nullptr;
  bool broken = false;  // a decompression error was met: nothing more can be read
  std::vector<char> chunk;
  std::string text;
  std::vector<std::string> fields;
  std::size_t line = 0;
  bool skipping_long_line = false;  // a line was too long: its rest is skipped by the next read
  double frontlaser_offset_m = 0.0;
  bool seen_laser = false;
  std::uintmax_t file_bytes = 0;
};

double CarmenReader::Progress() const {
  if (impl_->file_bytes == 0) return 0.0;
  const auto offset = gzoffset(impl_->file);  // compressed bytes consumed (plain files: bytes)
  return offset < 0 ? 0.0 : std::min(1.0, static_cast<double>(offset) / impl_->file_bytes);
}

CarmenReader::CarmenReader(const std::string& path, CarmenOptions options)
    : impl_(std::make_unique<Impl>(path, std::move(options))) {}
CarmenReader::~CarmenReader() = default;
CarmenReader::CarmenReader(CarmenReader&&) noexcept = default;
CarmenReader& CarmenReader::operator=(CarmenReader&&) noexcept = default;

bool CarmenReader::Next(CarmenRecord& record) {
  return impl_->Next(record);
}

std::size_t CarmenReader::lines_read() const {
  return impl_->line;
}

LaserMounting CarmenReader::mounting() const {
  LaserMounting mounting;
  mounting.T_robot_laser =
      Pose2D(impl_->options.laser_offset_m.value_or(impl_->frontlaser_offset_m), 0.0, 0.0);
  return mounting;
}

LaserScan ReadCarmenScan(const std::string& path, std::size_t index, CarmenOptions options) {
  CarmenReader reader(path, std::move(options));
  CarmenRecord record;
  std::size_t scans = 0;
  while (reader.Next(record)) {
    if (record.kind != CarmenRecord::Kind::kLaser) continue;
    if (scans == index) return std::move(record.scan);
    ++scans;
  }
  throw std::runtime_error("CARMEN log " + path + " holds " + std::to_string(scans) +
                           " laser scans; scan " + std::to_string(index) + " was asked for");
}

}  // namespace scanloc
