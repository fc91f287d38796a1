#pragma once
// What other commands read back from a finished run folder's summary.json.

#include <optional>
#include <string>

#include "scanloc/geometry/laser_scan.hpp"

namespace scanloc {

// The laser's mounting on the robot that the run was made with (summary.json's config.mounting).
// Nothing when the file does not exist or records no mounting. Throws std::runtime_error naming
// the file when it cannot be read, is not JSON, or its mounting is not three finite numbers.
std::optional<LaserMounting> ReadRunMounting(const std::string& summary_path);

}  // namespace scanloc
