#pragma once
// The off-line line map: segments in world coordinates, in a text format a person edits by hand.
//
// Format: one segment per line, `x1 y1 x2 y2` in metres; `#` starts a comment; blank lines are
// allowed. Example:
//     # classroom, north wall
//     0.0 6.0 8.0 6.0

#include <Eigen/Core>
#include <string>
#include <vector>

namespace scanloc {

struct Segment {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
  double Length() const { return (b - a).norm(); }
};

struct LineMap {
  std::vector<Segment> segments;
  bool empty() const { return segments.empty(); }
};

// Reads a line map; throws ParseError (file, line, what was expected) on malformed content and
// std::runtime_error when the file cannot be opened. An empty file gives an empty map.
LineMap ReadLineMap(const std::string& path);
// Writes atomically (temporary file, then rename).
void WriteLineMap(const LineMap& map, const std::string& path);

// §3.2.2 step 2: samples every segment at regular intervals no longer than `spacing_m`, vertices
// included. A degenerate (zero-length) segment gives its single point.
std::vector<Eigen::Vector2d> SampleLineMap(const LineMap& map, double spacing_m = 0.0075);

}  // namespace scanloc
