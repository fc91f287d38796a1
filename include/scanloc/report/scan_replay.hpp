#pragma once
// Re-reads a session's sequence to give the report each selected iteration's scan, with the map
// as it stood before that scan: the starting map extended, as the session extended it (ExtendMap:
// carving, then (3.6)), by the scans the session inserted, at the postures it kept.

#include <functional>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/report/run_records.hpp"
#include "scanloc/session/map_extension.hpp"

namespace scanloc {

struct ScanReplayResult {
  std::size_t scans_read = 0;
  std::size_t scans_visited = 0;
  // Why the replay stopped early ("" when it did not): unreadable log, fewer scans than
  // iterations, a scan that is not the one the run recorded.
  std::string problem;
};

using ScanVisitor =
    std::function<void(const IterationRow& row, const LaserScan& scan, const PointMap& map_before)>;

// Reads `log_path` (CARMEN or native sequence) iteration by iteration alongside `rows`, calls
// `visit` for every index in `selected` (any order), and extends `map` with the scans the session
// inserted, from mounting.LaserPose(T_world_robot), with the session's `extension` options. Stops
// after the last selected iteration. Problems with the log are returned, not thrown.
ScanReplayResult ReplayScans(const std::string& log_path, const std::vector<IterationRow>& rows,
                             const std::vector<std::size_t>& selected,
                             const LaserMounting& mounting, const MapExtensionOptions& extension,
                             PointMap& map, const ScanVisitor& visit);

}  // namespace scanloc
