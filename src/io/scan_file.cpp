#include "scanloc/io/scan_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/carmen_log.hpp"

namespace scanloc {
namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Reads numbers for a `ranges` or `reflectance` block, across lines, until `count` are read.
void ReadBlock(std::istream& in, const std::string& path, std::size_t& line_number,
               std::vector<std::string> rest, std::size_t count, const std::string& what,
               std::vector<double>& values) {
  values.clear();
  const std::size_t start_line = line_number;
  while (true) {
    for (const auto& field : rest) {
      if (values.size() == count)
        throw ParseError(path, line_number, "more than " + std::to_string(count) + " " + what);
      values.push_back(ParseDouble(field, path, line_number, what + " value"));
    }
    if (values.size() == count) return;
    std::string line;
    if (!ReadBoundedLine(in, line, path, line_number + 1))
      throw ParseError(path, start_line,
                       "expected " + std::to_string(count) + " " + what + ", file ended after " +
                           std::to_string(values.size()));
    ++line_number;
    rest = SplitFields(line, count - values.size());
  }
}

// The value of a 'beams <count>' line: a count in [1, kMaxBeamsPerScan].
long ParseBeamCount(const std::vector<std::string>& fields, const std::string& path,
                    std::size_t number) {
  if (fields.size() != 2) throw ParseError(path, number, "expected 'beams <count>'");
  const long beams = ParseInteger(fields[1], path, number, "a beam count");
  if (beams < 1 || beams > static_cast<long>(kMaxBeamsPerScan))
    throw ParseError(path, number,
                     "expected a beam count in [1, " + std::to_string(kMaxBeamsPerScan) +
                         "] (kMaxBeamsPerScan)");
  return beams;
}

}  // namespace

LaserScan ReadScanFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open scan file " + path);
  LaserScan scan;
  std::optional<long> beams;
  std::optional<double> angle_min, angle_increment;
  bool have_header = false, have_ranges = false;
  std::string last_block;  // the block just read, to name an excess of values after it
  std::string line;
  std::size_t number = 0;
  while (ReadBoundedLine(in, line, path, number + 1)) {
    ++number;
    // A key line has a few fields; a `ranges` line at most the beam cap of values after its key.
    auto fields = SplitFields(line, kMaxBeamsPerScan + 1);
    if (fields.empty()) continue;
    const std::string key = fields[0];
    if (!have_header) {
      if (key != "scanloc_scan" || fields.size() != 2 || fields[1] != "1")
        throw ParseError(path, number, "expected the header 'scanloc_scan 1'");
      have_header = true;
      continue;
    }
    auto value = [&](const std::string& what) {
      if (fields.size() != 2)
        throw ParseError(path, number, "expected '" + key + " <" + what + ">'");
      return ParseFiniteDouble(fields[1], path, number, what);
    };
    if (key == "beams") {
      beams = ParseBeamCount(fields, path, number);
    } else if (key == "angle_min_rad") {
      angle_min = value("first bearing in radians");
    } else if (key == "angle_increment_rad") {
      angle_increment = value("bearing step in radians");
      if (!(*angle_increment > 0.0)) throw ParseError(path, number, "expected a positive step");
    } else if (key == "range_min_m") {
      scan.layout.range_min_m = value("minimum range in metres");
    } else if (key == "range_max_m") {
      scan.layout.range_max_m = value("maximum range in metres");
    } else if (key == "timestamp_s") {
      scan.timestamp_s = value("timestamp in seconds");
    } else if (key == "ranges" || key == "reflectance") {
      if (!beams) throw ParseError(path, number, "'beams' must come before '" + key + "'");
      fields.erase(fields.begin());
      ReadBlock(in, path, number, fields, static_cast<std::size_t>(*beams), key,
                key == "ranges" ? scan.ranges_m : scan.reflectance);
      have_ranges = have_ranges || key == "ranges";
      last_block = key;
      continue;
    } else {
      char* end = nullptr;
      std::strtod(key.c_str(), &end);
      if (!last_block.empty() && end != key.c_str() && *end == '\0')
        throw ParseError(path, number,
                         "more than " + std::to_string(*beams) + " " + last_block +
                             " values (beams " + std::to_string(*beams) + ")");
      throw ParseError(path, number, "unknown key '" + key + "'");
    }
    last_block.clear();
  }
  if (!have_header)
    throw ParseError(path, std::max<std::size_t>(number, 1),
                     "empty scan file: expected 'scanloc_scan 1'");
  if (!beams || !angle_min || !angle_increment || !have_ranges)
    throw ParseError(path, number,
                     "incomplete scan: 'beams', 'angle_min_rad', 'angle_increment_rad' and "
                     "'ranges' are required");
  scan.layout.beam_count = static_cast<std::size_t>(*beams);
  scan.layout.angle_min_rad = *angle_min;
  scan.layout.angle_increment_rad = *angle_increment;
  try {
    scan.CheckConsistent();
  } catch (const std::invalid_argument& e) {
    throw ParseError(path, number, e.what());
  }
  return scan;
}

void WriteScanFile(const LaserScan& scan, const std::string& path) {
  scan.CheckConsistent();
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << std::setprecision(15);
    out << "scanloc_scan 1\n";
    out << "beams " << scan.size() << '\n';
    out << "angle_min_rad " << scan.layout.angle_min_rad << '\n';
    out << "angle_increment_rad " << scan.layout.angle_increment_rad << '\n';
    out << "range_min_m " << scan.layout.range_min_m << '\n';
    out << "range_max_m " << scan.layout.range_max_m << '\n';
    out << "timestamp_s " << scan.timestamp_s << '\n';
    auto block = [&](const char* name, const std::vector<double>& values) {
      out << name << '\n';
      char text[32];
      for (std::size_t i = 0; i < values.size(); ++i) {
        // The shortest text that reads back to the same double: 19.9999996 must not become 20.
        const auto end = std::to_chars(text, text + sizeof text, values[i]).ptr;
        out.write(text, end - text);
        out << ((i + 1) % 10 == 0 || i + 1 == values.size() ? '\n' : ' ');
      }
    };
    block("ranges", scan.ranges_m);
    if (!scan.reflectance.empty()) block("reflectance", scan.reflectance);
  });
}

LaserScan LoadScan(const std::string& path, std::size_t carmen_index, const CarmenOptions& carmen) {
  for (const char* suffix : {".clf", ".clf.gz", ".log", ".log.gz"})
    if (EndsWith(path, suffix)) return ReadCarmenScan(path, carmen_index, carmen);
  if (carmen_index != 0)
    throw std::runtime_error(path +
                             ": a scan index is only meaningful for CARMEN logs "
                             "(.clf, .clf.gz, .log, .log.gz)");
  return ReadScanFile(path);
}

}  // namespace scanloc
