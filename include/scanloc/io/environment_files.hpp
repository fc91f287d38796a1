#pragma once
// An environment as files: what `scanloc simulate` writes and datasets/<environment>/ holds.
//
//   <name>.lines       the line map the localisation is given
//   world.lines        every segment the simulated laser sees
//   <addition>.lines   lines an operator may add to the map (the office's blinds.lines)
//   <name>.seq.jsonl   the native sequence: scans, odometry and ground truth (sequence_sources.hpp)

#include <cstddef>
#include <string>
#include <vector>

#include "scanloc/worlds/environments.hpp"

namespace scanloc {

// The text of a line file: "# " before every header line and group comment, one "x1 y1 x2 y2"
// line per segment with two decimals. Throws std::invalid_argument when a coordinate is not a
// whole number of centimetres (two decimals would change the world the scans were taken of).
std::string FormatLineFile(const LineFile& file);

struct EnvironmentFiles {
  std::vector<std::string> paths;  // every file written, the sequence last
  std::size_t iterations = 0;
};

// Simulates the environment with `seed` and writes its files into `directory` (created when
// missing), each atomically. `max_iterations` > 0 cuts the path short.
EnvironmentFiles WriteEnvironmentFiles(const Environment& environment, unsigned seed,
                                       const std::string& directory,
                                       std::size_t max_iterations = 0);

}  // namespace scanloc
