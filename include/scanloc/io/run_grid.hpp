#pragma once
// The occupancy grid of a session's run folder: which scans it is cast from (the same rule for the
// grid a session writes as it runs and for `scanloc export-grid`), and the grid rebuilt afterwards
// from a run folder and its log.

#include <string>

#include "scanloc/io/occupancy_grid_io.hpp"

namespace scanloc {

// A session's grid is cast from the scans that built its point map: the validated ones, and the
// first, which starts the map.
inline bool CastIntoGrid(bool validated, bool first) {
  return validated || first;
}

struct RunGridRequest {
  std::string run_dir;
  std::string log_path;    // "" for the log summary.json names
  bool all_scans = false;  // every localised scan, not only those CastIntoGrid picks
  OccupancyGridOptions options;
};

struct RunGrid {
  GridFromLogResult built;
  std::string log_path;             // the log the scans came from ("" when simulated)
  bool simulated_from_map = false;  // the log was absent: scans simulated from map.pcd
};

// Reads the run folder's summary.json (the log and the mounting in force), trajectory.tum and
// iterations.jsonl, and casts the log's scans at the kept postures. Without the log, scans are
// simulated from map.pcd (720 beams over a full turn, 30 m) at the same postures. Throws
// std::runtime_error naming the file when the folder lacks what is needed, or when no scan of the
// log has a posture in the trajectory.
RunGrid BuildRunFolderGrid(const RunGridRequest& request);

}  // namespace scanloc
