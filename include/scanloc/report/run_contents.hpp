#pragma once
// Everything the report shows from a run folder (what `scanloc session --out DIR` writes):
// iterations.jsonl, summary.json, map.pcd, map.yaml + map.pgm, and the inputs summary.json names.
// Only a missing or malformed iterations.jsonl is an error; anything else missing is said in
// `notes` and the rest still renders.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scanloc/config/config.hpp"
#include "scanloc/io/occupancy_grid_io.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/report/run_records.hpp"

namespace scanloc {

// Paths given on the command line, used instead of those summary.json names ("" for none).
struct RunInputOverrides {
  std::string log_path;
  std::string line_map_path;
};

struct RunContents {
  std::string directory;
  nlohmann::json summary = nlohmann::json::object();  // {} when summary.json is missing
  Config config;  // the session's configuration (the defaults when unknown)
  IterationRows iterations;
  std::vector<Eigen::Vector2d> final_map;  // map.pcd, world coordinates
  std::optional<OccupancyGridImage> grid;  // map.yaml + map.pgm; none in older run folders
  LineMap line_map;                        // empty when the session used none
  std::string log_path;                    // the sequence, found on disk; "" when unavailable
  std::string point_map_path;      // the map the session started from; "" when none or not found
  std::vector<std::string> notes;  // what is missing or unreadable, for the page
};

// Throws std::runtime_error when the folder or its iterations.jsonl is missing, ParseError (file,
// line, what was expected) when a line of iterations.jsonl or summary.json is malformed.
RunContents ReadRunContents(const std::string& directory, const RunInputOverrides& overrides = {});

}  // namespace scanloc
