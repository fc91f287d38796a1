#pragma once
// What other commands read back from a finished run folder's summary.json.

#include <optional>
#include <string>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/session/map_signature.hpp"

namespace scanloc {

// The laser's mounting on the robot that the run was made with (summary.json's config.mounting).
// Nothing when the file does not exist or records no mounting. Throws std::runtime_error naming
// the file when it cannot be read, is not JSON, or its mounting is not three finite numbers.
std::optional<LaserMounting> ReadRunMounting(const std::string& summary_path);

// The map's own signature (summary.json's map_signature, written by the session that built the
// map: session/map_signature.hpp): its rule-2 bound, median EV and sampled scans (none in a file
// written before they were kept). Nothing when the file does not exist or holds no signature
// learned from enough scans. Throws std::runtime_error naming the file when it cannot be read, is
// not JSON, the bound is not a positive number or a sample is not three finite numbers.
std::optional<MapSignature> ReadMapSignature(const std::string& summary_path);

}  // namespace scanloc
