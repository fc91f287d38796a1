#pragma once
// The top-level configuration: every stage's options with their defaults, loadable from a JSON
// file whose keys mirror the fields (any subset; unknown keys are refused with their path).
//
//     { "likelihood_test": { "slot_count": 20, "match_threshold_m": 0.4 },
//       "validation": { "min_match_ratio": 0.2 } }
//
// Each option is declared once (src/config/option_table.hpp: key, field, sane range, meaning);
// the reader, the writer and the help text (`scanloc options`) are derived from that declaration.

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/io/carmen_log.hpp"
#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/maps/occupancy_grid.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/refinement/refiner.hpp"
#include "scanloc/session/localiser.hpp"
#include "scanloc/session/session.hpp"

namespace scanloc {

struct Config {
  ScoringOptions scoring;           // likelihood_test, likelihood_distance, point_simulation
  ValidationOptions validation;     // validation (rules 1–5, α of (3.11) for Error Descent too)
  PointMapOptions point_map;        // point_map
  double line_sampling_m = 0.0075;  // spacing when a line map is sampled to points (§3.2.2)
  LaserMounting mounting;           // mounting: {"x_m", "y_m", "yaw_rad"} of the laser on the robot
  // refinement: {"method", "ceres": {...}, "error_descent": {...}, "icp": {...}}
  RefinerOptions refiner;
  SessionOptions session;     // session
  LocaliserOptions localise;  // localise: the global search and the hypotheses (scanloc localise)
  CarmenOptions log;          // log: how CARMEN logs are read
  // occupancy_grid: the map_server grid (map.pgm + map.yaml) a session writes into its run folder
  bool write_occupancy_grid = true;
  OccupancyGridOptions occupancy_grid;

  // Throws std::invalid_argument naming the first option out of its range or domain.
  void Validate() const;
};

// Overlays the keys of a JSON object onto `config`; throws std::runtime_error naming the key path
// for unknown (or moved) keys, values of the wrong type and values out of their sane range.
void ApplyJson(const nlohmann::json& json, Config& config);
// Reads a JSON config file on top of the defaults; errors (invalid JSON, a key given twice, any
// error of ApplyJson or Validate) name the file.
Config LoadConfig(const std::string& path);
nlohmann::json ToJson(const Config& config);

// One option as the help text shows it.
struct OptionDescription {
  std::string key;            // its path in the JSON config, e.g. "likelihood_test.slot_count"
  std::string default_value;  // as JSON, e.g. "20"
  std::string accepted;       // e.g. "[2, 10000]", "true or false", "a name"
  std::string meaning;        // what it does, with its unit
};
// Every option, in the order of the help text.
std::vector<OptionDescription> DescribeOptions();
// Every option's key, default, accepted values and meaning, for `scanloc options`.
std::string OptionsHelp();

}  // namespace scanloc
