#include "scanloc/maps/line_map.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"

namespace scanloc {

LineMap ReadLineMap(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open line map " + path);
  LineMap map;
  std::string line;
  for (std::size_t number = 1; ReadBoundedLine(in, line, path, number); ++number) {
    const auto fields = SplitFields(line, 4);
    if (fields.empty()) continue;
    if (fields.size() != 4)
      throw ParseError(path, number,
                       "expected 4 numbers 'x1 y1 x2 y2' (metres), got " +
                           std::to_string(fields.size()) + " fields");
    const char* names[] = {"x1 in metres", "y1 in metres", "x2 in metres", "y2 in metres"};
    double v[4];
    for (int i = 0; i < 4; ++i) v[i] = ParseFiniteDouble(fields[i], path, number, names[i]);
    map.segments.push_back({{v[0], v[1]}, {v[2], v[3]}});
  }
  if (in.bad()) throw std::runtime_error("error while reading " + path);
  return map;
}

void WriteLineMap(const LineMap& map, const std::string& path) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# scanloc line map: x1 y1 x2 y2 (metres), one segment per line\n";
    out << std::setprecision(9);
    for (const auto& s : map.segments)
      out << s.a.x() << ' ' << s.a.y() << ' ' << s.b.x() << ' ' << s.b.y() << '\n';
  });
}

std::vector<Eigen::Vector2d> SampleLineMap(const LineMap& map, double spacing_m) {
  if (!(spacing_m > 0.0) || !std::isfinite(spacing_m))
    throw std::invalid_argument("SampleLineMap: spacing_m must be positive and finite");
  std::vector<Eigen::Vector2d> points;
  for (const auto& s : map.segments) {
    const double length = s.Length();
    const double count = std::ceil(length / spacing_m);
    // A segment of 10 km at the default spacing is 1.3 M points; past that it is an input error.
    if (!std::isfinite(count) || count > 1e7)
      throw std::invalid_argument("SampleLineMap: a segment of " + std::to_string(length) +
                                  " m would need more than 10 million samples");
    const auto intervals = static_cast<std::size_t>(count);
    if (intervals == 0) {
      points.push_back(s.a);
      continue;
    }
    for (std::size_t k = 0; k <= intervals; ++k)
      points.push_back(s.a + (s.b - s.a) * (static_cast<double>(k) / intervals));
  }
  return points;
}

}  // namespace scanloc
