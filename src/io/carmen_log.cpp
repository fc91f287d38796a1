#include "scanloc/io/carmen_log.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "carmen_messages.hpp"
#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/carmen_saturation.hpp"

namespace scanloc {
namespace {

using carmen::LaserMessage;
using carmen::MessageFields;

// gzgets reads at most this much per call; longer lines are assembled from several calls.
constexpr int kReadChunkBytes = 64 * 1024;
// zlib's internal buffer: large enough that decompression is not the bottleneck.
constexpr unsigned kGzipBufferBytes = 256 * 1024;

// The look-ahead at open: at most this many lines and laser scans, and the readings of at most
// this many beams, are read to choose the laser message and recognise the saturation code.
constexpr std::size_t kPreviewLines = 20000;
constexpr std::size_t kPreviewScans = 200;
constexpr std::size_t kPreviewReadings = 200000;

// Skipped message types are counted under their first kMaxTagBytes bytes; beyond
// kMaxSkippedTypes distinct types (a garbage file), under kOtherTypes.
constexpr std::size_t kMaxTagBytes = 32;
constexpr std::size_t kMaxSkippedTypes = 64;
constexpr char kOtherTypes[] = "(other)";

// What the look-ahead found.
struct LogPreview {
  std::optional<LaserMessage> laser;  // the preferred laser message met; nullopt: none met
  std::optional<double> saturation_m;
};

}  // namespace

void CarmenOptions::Validate() const {
  if (!(max_range_m > 0.0) || !std::isfinite(max_range_m))
    throw std::invalid_argument("CarmenOptions: max_range_m must be positive and finite, got " +
                                std::to_string(max_range_m));
  if (no_return_m && (!(*no_return_m > 0.0) || !std::isfinite(*no_return_m)))
    throw std::invalid_argument("CarmenOptions: no_return_m must be positive and finite, got " +
                                std::to_string(*no_return_m));
  if (laser_offset_m && !std::isfinite(*laser_offset_m))
    throw std::invalid_argument("CarmenOptions: laser_offset_m must be finite");
}

struct CarmenReader::Impl {
  // `preview`: what the look-ahead found; unset for the look-ahead itself, which reads every laser
  // kind and stops after kPreviewLines lines.
  Impl(const std::string& log_path, CarmenOptions reader_options,
       std::optional<LogPreview> preview = std::nullopt)
      : path(log_path), options(reader_options), chunk(kReadChunkBytes) {
    options.Validate();
    previewing = !preview.has_value();
    if (preview) {
      laser = preview->laser;
      recognised_no_return_m = preview->saturation_m;
    }
    no_return_m = options.no_return_m ? options.no_return_m : recognised_no_return_m;
    flaser_range_max_m = std::min(options.max_range_m, no_return_m.value_or(options.max_range_m));
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
    if (previewing && line >= kPreviewLines) return false;
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
      SplitFields(text, carmen::kMaxMessageFields, fields);  // also drops `#` comments
      if (fields.empty()) continue;
      const MessageFields message(fields, path, line);
      if (fields.size() > carmen::kMaxMessageFields)
        message.Fail("more than " + std::to_string(carmen::kMaxMessageFields) +
                     " fields in one message: a scan has at most " +
                     std::to_string(kMaxBeamsPerScan) + " beams (kMaxBeamsPerScan)");
      if (!Parse(message, record)) continue;
      if (record.has_odometry && !IsPlausiblePose(record.odometry))
        message.Fail("odometry beyond ±" + std::to_string(static_cast<long>(kMaxCoordinateM)) +
                     " m, expected a planar posture in metres");
      record.line = line;
      if (record.kind == CarmenRecord::Kind::kLaser) {
        record.scan.timestamp_s = record.timestamp_s;
        seen_laser = true;
      } else {
        last_odometry = record.odometry;
      }
      return true;
    }
    return false;
  }

  // Fills `record` from a laser or ODOM message; false for the messages that make no record.
  bool Parse(const MessageFields& message, CarmenRecord& record) {
    const std::string& type = message[0];
    if (type == "ODOM") {
      carmen::ParseOdometry(message, record);
      return true;
    }
    if (type == "PARAM") {
      ParseParam(message);
      return false;
    }
    const std::optional<LaserMessage> kind = carmen::LaserMessageOf(type);
    if (!kind || !Reads(*kind)) {
      CountSkipped(type);
      return false;
    }
    last_laser = *kind;
    switch (*kind) {
      case LaserMessage::kFlaser:
        carmen::ParseFlaser(message, flaser_range_max_m, record);
        break;
      case LaserMessage::kRobotLaser1:
        carmen::ParseRobotLaser(message, no_return_m, record);
        break;
      case LaserMessage::kRawLaser1:
        carmen::ParseRawLaser(message, no_return_m, record);
        record.has_odometry = last_odometry.has_value();
        record.odometry = last_odometry.value_or(Pose2D{});
        break;
    }
    return true;
  }

  // Whether this laser kind is the one read (the look-ahead reads them all; without a kind from
  // the look-ahead, the first one met is read).
  bool Reads(LaserMessage kind) {
    if (previewing) return true;
    if (!laser) laser = kind;
    return *laser == kind;
  }

  void CountSkipped(const std::string& type) {
    std::string key = type.substr(0, kMaxTagBytes);
    if (skipped.size() >= kMaxSkippedTypes && skipped.count(key) == 0) key = kOtherTypes;
    ++skipped[key];
  }

  void ParseParam(const MessageFields& message) {
    const std::optional<double> offset_m = carmen::ParseLaserOffsetParam(message);
    if (!offset_m) return;
    // Scans already returned were read with the mounting in force then: it stays.
    if (seen_laser) {
      if (*offset_m != frontlaser_offset_m) ++ignored_laser_offsets;
      return;
    }
    frontlaser_offset_m = *offset_m;
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

  bool previewing = false;            // the look-ahead: every laser kind, bounded lines
  std::optional<LaserMessage> laser;  // the laser message read
  LaserMessage last_laser = LaserMessage::kFlaser;  // the kind of the last laser record
  std::optional<Pose2D> last_odometry;              // the latest ODOM's pose, for RAWLASER1
  std::optional<double> recognised_no_return_m;
  std::optional<double> no_return_m;  // options.no_return_m, else the recognised value
  double flaser_range_max_m = 0.0;
  std::map<std::string, std::size_t> skipped;
  std::size_t ignored_laser_offsets = 0;

  // Reads the log's first lines (kPreviewLines, kPreviewScans): the laser kinds it carries and,
  // when wanted, its saturation code. Malformed lines are passed over here; the reader reports
  // them.
  static LogPreview ReadAhead(const std::string& path, const CarmenOptions& options) {
    Impl impl(path, options);
    std::set<LaserMessage> kinds;
    std::vector<BeamReading> readings;
    std::size_t scans = 0;
    CarmenRecord record;
    while (scans < kPreviewScans) {
      try {
        if (!impl.Next(record)) break;
      } catch (const ParseError&) {
        continue;  // a corrupt stream makes the next Next() return false
      }
      if (record.kind != CarmenRecord::Kind::kLaser) continue;
      ++scans;
      kinds.insert(impl.last_laser);
      const std::vector<double>& ranges = record.scan.ranges_m;
      for (std::size_t i = 0; i < ranges.size() && readings.size() < kPreviewReadings; ++i)
        readings.push_back({ranges[i], i});
    }
    LogPreview preview;
    if (!kinds.empty())
      preview.laser = *kinds.begin();  // the enumeration's order is the preference
    if (options.detect_no_return && !options.no_return_m)
      preview.saturation_m = RecogniseSaturation(readings);
    return preview;
  }
};

double CarmenReader::Progress() const {
  if (impl_->file_bytes == 0) return 0.0;
  const auto offset = gzoffset(impl_->file);  // compressed bytes consumed (plain files: bytes)
  return offset < 0 ? 0.0 : std::min(1.0, static_cast<double>(offset) / impl_->file_bytes);
}

CarmenReader::CarmenReader(const std::string& path, CarmenOptions options) {
  const LogPreview preview = Impl::ReadAhead(path, options);
  impl_ = std::make_unique<Impl>(path, std::move(options), preview);
}
CarmenReader::~CarmenReader() = default;
CarmenReader::CarmenReader(CarmenReader&&) noexcept = default;
CarmenReader& CarmenReader::operator=(CarmenReader&&) noexcept = default;

bool CarmenReader::Next(CarmenRecord& record) {
  return impl_->Next(record);
}

std::size_t CarmenReader::lines_read() const {
  return impl_->line;
}

std::optional<double> CarmenReader::recognised_no_return_m() const {
  return impl_->recognised_no_return_m;
}

double CarmenReader::no_return_m() const {
  return impl_->flaser_range_max_m;
}

const std::map<std::string, std::size_t>& CarmenReader::skipped_messages() const {
  return impl_->skipped;
}

std::size_t CarmenReader::ignored_laser_offsets() const {
  return impl_->ignored_laser_offsets;
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
