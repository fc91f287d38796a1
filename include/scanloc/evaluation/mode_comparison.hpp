#pragma once
// The map modes compared on a sequence with ground truth: the same iterations localised against
// the fixed line map, against a point map grown from nothing, and against both; each run measured
// against the truth (`scanloc compare`).

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "scanloc/config/config.hpp"
#include "scanloc/maps/line_map.hpp"

namespace scanloc {

enum class MapMode {
  kLineMap,   // the line map only, never extended
  kPointMap,  // a point map grown from nothing by the validated scans (3.6)
  kBoth,      // the line map and the growing point map
};
const char* ToString(MapMode mode);  // "line map", "point map", "both"
// Parses "lines", "points" or "both"; throws std::invalid_argument otherwise.
MapMode ParseMapMode(const std::string& name);

struct ModeResult {
  MapMode mode = MapMode::kLineMap;
  std::size_t iterations = 0;  // processed
  std::size_t localised = 0;   // tested and refined (not skipped, not the given first posture)
  std::size_t validated = 0;   // localised and validated (IterationRecord::validated)
  // Posture error against the truth, T_world_robot, over the iterations with truth except the
  // first of a run without a prior map (its posture is given, not estimated).
  std::size_t with_truth = 0;
  double mean_translation_error_m = 0.0, max_translation_error_m = 0.0;
  double mean_rotation_error_rad = 0.0, max_rotation_error_rad = 0.0;
  // The Likelihood Test of the refined posture, averaged over the localised iterations.
  double mean_match_pairs = 0.0, mean_valid_pairs = 0.0;
  double mean_match_ratio = 0.0;  // mean of MP/NVP per iteration
  double mean_expect_value_m = 0.0;
  double mean_iteration_s = 0.0;  // session time per iteration (reading the file excluded)
  std::size_t map_points = 0;     // point map size at the end
};

// Runs the native sequence at `sequence_path` in one mode. The run starts at the first
// iteration's true posture (SessionOptions::initial_pose), so that the modes' errors compare; the
// laser mounting is the sequence's. `max_iterations` > 0 stops early. Throws ParseError for a
// malformed sequence and std::invalid_argument when a mode needing the line map gets none.
ModeResult RunMode(MapMode mode, const std::string& sequence_path, const LineMap& line_map,
                   const Config& config, std::size_t max_iterations = 0);

// One row per result: iterations, localised, validated, translation and rotation errors (mean,
// max), MP/NVP, EV and time per iteration.
void PrintComparison(std::ostream& out, const std::vector<ModeResult>& results);

}  // namespace scanloc
