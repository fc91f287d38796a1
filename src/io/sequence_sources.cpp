#include "scanloc/io/sequence_sources.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/input_format.hpp"

namespace scanloc {
namespace {

using nlohmann::json;

// Numbers a line may hold besides a scan's ranges and reflectance at the beam cap: thousands of
// candidates. A line with more commas is refused before it is parsed (a JSON number costs 16 bytes
// and more once parsed, a comma one byte of text).
constexpr std::size_t kMaxOtherNumbersPerLine = 100000;
constexpr std::size_t kMaxCommasPerLine = 2 * kMaxBeamsPerScan + kMaxOtherNumbersPerLine;

Pose2D ParsePose(const json& value, const std::string& path, std::size_t line, const char* what) {
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
      !value[2].is_number())
    throw ParseError(path, line, std::string(what) + ": expected [x_m, y_m, yaw_rad]");
  const Pose2D pose{value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
  if (!IsPlausiblePose(pose))
    throw ParseError(path, line,
                     std::string(what) + ": expected finite numbers with |x|, |y| <= " +
                         std::to_string(static_cast<long>(kMaxCoordinateM)) + " m");
  return pose;
}

json PoseJson(const Pose2D& p) {
  return json::array({p.x_m, p.y_m, p.yaw_rad});
}

double Number(const json& object, const char* key, const std::string& path, std::size_t line,
              std::optional<double> fallback = std::nullopt) {
  const auto it = object.find(key);
  if (it == object.end()) {
    if (fallback) return *fallback;
    throw ParseError(path, line, std::string("scan: missing '") + key + "'");
  }
  if (!it->is_number() || !std::isfinite(it->get<double>()))
    throw ParseError(path, line, std::string("scan: '") + key + "' must be a finite number");
  return it->get<double>();
}

std::vector<double> Values(const json& array, const std::string& path, std::size_t line,
                           const char* what) {
  if (!array.is_array()) throw ParseError(path, line, std::string(what) + ": expected an array");
  std::vector<double> values;
  values.reserve(array.size());
  for (const auto& v : array) {
    if (v.is_null())
      values.push_back(-1.0);
    else if (v.is_number())
      values.push_back(v.get<double>());
    else
      throw ParseError(path, line, std::string(what) + ": expected numbers (or null)");
  }
  return values;
}

// The "scan" object of an iteration: its layout and at least one beam.
void ParseScan(const json& scan, const std::string& path, std::size_t line, LaserScan& s) {
  s.layout.angle_min_rad = Number(scan, "angle_min_rad", path, line);
  s.layout.angle_increment_rad = Number(scan, "angle_increment_rad", path, line);
  s.layout.range_min_m = Number(scan, "range_min_m", path, line, 0.0);
  s.layout.range_max_m = Number(scan, "range_max_m", path, line, 20.0);
  if (!scan.contains("ranges")) throw ParseError(path, line, "scan: missing 'ranges'");
  s.ranges_m = Values(scan["ranges"], path, line, "scan.ranges");
  if (s.ranges_m.empty())
    throw ParseError(path, line, "scan: 'ranges' is empty, expected at least one beam");
  if (scan.contains("reflectance"))
    s.reflectance = Values(scan["reflectance"], path, line, "scan.reflectance");
  s.layout.beam_count = s.ranges_m.size();
  try {
    s.CheckConsistent();
  } catch (const std::invalid_argument& e) {
    throw ParseError(path, line, e.what());
  }
}

}  // namespace

CarmenIterationSource::CarmenIterationSource(const std::string& path, CarmenOptions options)
    : path_(path), repair_(options.repair_reversed_odometry), reader_(path, std::move(options)) {}

bool CarmenIterationSource::Next(Iteration& iteration) {
  CarmenRecord record;
  while (reader_.Next(record)) {
    if (record.kind != CarmenRecord::Kind::kLaser) {
      if (record.velocity_mps)
        reversal_.AddOdometry(record.odometry, *record.velocity_mps, record.timestamp_s);
      continue;
    }
    iteration = Iteration{};
    iteration.timestamp_s = record.timestamp_s;
    iteration.scan = std::move(record.scan);
    if (record.has_odometry)
      iteration.odometry =
          repair_ ? reversal_.Repair(record.odometry, record.velocity_mps, record.timestamp_s)
                  : record.odometry;
    iteration.origin = path_ + ":" + std::to_string(record.line);
    timestamps_.Add(iteration.timestamp_s);
    return true;
  }
  if (timestamps_.count() == 0)
    throw ParseError(
        path_, std::max<std::size_t>(reader_.lines_read(), 1),
        "no scan in " + path_ + ": expected FLASER, ROBOTLASER1 or RAWLASER1 messages");
  return false;
}

struct SequenceFileSource::Impl {
  std::string path;
  std::ifstream in;
  std::size_t line = 0;
  std::uintmax_t bytes = 0;
};

SequenceFileSource::SequenceFileSource(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->in.open(path);
  if (!impl_->in) throw std::runtime_error("cannot open sequence " + path);
  std::error_code error;
  impl_->bytes = std::filesystem::file_size(path, error);
  std::string text;
  while (ReadBoundedLine(impl_->in, text, path, impl_->line + 1)) {
    ++impl_->line;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    json header;
    try {
      header = json::parse(text);
    } catch (const json::exception&) {
      throw ParseError(path, impl_->line, "expected the header {\"scanloc_sequence\": 1, ...}");
    }
    // The version is compared as JSON: value<int>() would convert 3e40 (undefined) or throw on
    // an array.
    if (!header.is_object() || !header.contains("scanloc_sequence") ||
        header.at("scanloc_sequence") != json(1))
      throw ParseError(path, impl_->line, "expected the header {\"scanloc_sequence\": 1, ...}");
    if (header.contains("mounting"))
      mounting_.T_robot_laser = ParsePose(header["mounting"], path, impl_->line, "mounting");
    return;
  }
  throw ParseError(path, std::max<std::size_t>(impl_->line, 1),
                   "empty sequence: expected the header {\"scanloc_sequence\": 1, ...}");
}

SequenceFileSource::~SequenceFileSource() = default;

double SequenceFileSource::Progress() const {
  if (impl_->bytes == 0) return 0.0;
  const auto position = impl_->in.tellg();
  return position < 0 ? 1.0 : std::min(1.0, static_cast<double>(position) / impl_->bytes);
}

bool SequenceFileSource::Next(Iteration& iteration) {
  const std::string& path = impl_->path;
  std::string text;
  while (ReadBoundedLine(impl_->in, text, path, impl_->line + 1)) {
    const std::size_t line = ++impl_->line;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) > kMaxCommasPerLine)
      throw ParseError(path, line,
                       "more than " + std::to_string(kMaxCommasPerLine) +
                           " numbers on one line: a scan has at most " +
                           std::to_string(kMaxBeamsPerScan) + " beams (kMaxBeamsPerScan)");
    json record;
    try {
      record = json::parse(text);
    } catch (const json::exception& e) {
      throw ParseError(path, line, std::string("expected one JSON object per line: ") + e.what());
    }
    if (!record.is_object() || !record.contains("scan") || !record["scan"].is_object())
      throw ParseError(path, line, "expected an object with a \"scan\" object");
    iteration = Iteration{};
    iteration.timestamp_s = Number(record, "timestamp_s", path, line, 0.0);
    ParseScan(record["scan"], path, line, iteration.scan);
    iteration.scan.timestamp_s = iteration.timestamp_s;
    if (record.contains("odometry"))
      iteration.odometry = ParsePose(record["odometry"], path, line, "odometry");
    if (record.contains("candidates")) {
      if (!record["candidates"].is_array())
        throw ParseError(path, line, "candidates: expected an array of [x_m, y_m, yaw_rad]");
      for (const auto& c : record["candidates"])
        iteration.external_candidates.push_back(ParsePose(c, path, line, "candidates"));
    }
    truth_.reset();
    if (record.contains("truth")) truth_ = ParsePose(record["truth"], path, line, "truth");
    iteration.origin = path + ":" + std::to_string(line);
    timestamps_.Add(iteration.timestamp_s);
    return true;
  }
  if (impl_->in.bad()) throw std::runtime_error("error while reading " + path);
  if (timestamps_.count() == 0)
    throw ParseError(path, std::max<std::size_t>(impl_->line, 1),
                     "no scan in " + path + ": expected iterations after the header");
  return false;
}

struct SequenceFileWriter::Impl {
  explicit Impl(const std::string& path) : file(path) {}
  AtomicFileWriter file;
};

SequenceFileWriter::SequenceFileWriter(const std::string& path, const LaserMounting& mounting)
    : impl_(std::make_unique<Impl>(path)) {
  impl_->file.stream()
      << json{{"scanloc_sequence", 1}, {"mounting", PoseJson(mounting.T_robot_laser)}}.dump()
      << '\n';
}

// Abandoned without Close(): the temporary is removed, nothing half-written is left behind.
SequenceFileWriter::~SequenceFileWriter() = default;

void SequenceFileWriter::Write(const Iteration& iteration, const std::optional<Pose2D>& truth) {
  const LaserScan& s = iteration.scan;
  json ranges = json::array();
  for (const double r : s.ranges_m) ranges.push_back(std::isfinite(r) ? json(r) : json(nullptr));
  json scan = {{"angle_min_rad", s.layout.angle_min_rad},
               {"angle_increment_rad", s.layout.angle_increment_rad},
               {"range_min_m", s.layout.range_min_m},
               {"range_max_m", s.layout.range_max_m},
               {"ranges", ranges}};
  if (!s.reflectance.empty()) scan["reflectance"] = s.reflectance;
  json record = {{"timestamp_s", iteration.timestamp_s}, {"scan", scan}};
  if (iteration.odometry) record["odometry"] = PoseJson(*iteration.odometry);
  if (!iteration.external_candidates.empty()) {
    json candidates = json::array();
    for (const auto& c : iteration.external_candidates) candidates.push_back(PoseJson(c));
    record["candidates"] = candidates;
  }
  if (truth) record["truth"] = PoseJson(*truth);
  impl_->file.stream() << record.dump() << '\n';
}

void SequenceFileWriter::Close() {
  impl_->file.Commit();
}

std::unique_ptr<IterationSource> OpenIterationSource(const std::string& path, CarmenOptions carmen,
                                                     RosBagOptions bag) {
  switch (DetectInputFormat(path)) {
    case InputFormat::kCarmenLog:
      return std::make_unique<CarmenIterationSource>(path, carmen);
    case InputFormat::kRosBag:
      return std::make_unique<RosBagIterationSource>(path, std::move(bag));
    case InputFormat::kScanSequence:
      break;
  }
  return std::make_unique<SequenceFileSource>(path);
}

}  // namespace scanloc
