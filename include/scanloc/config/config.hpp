#pragma once
// The top-level configuration: every stage's options with their defaults, loadable from a JSON
// file whose keys mirror the fields (any subset; unknown keys are refused with their path).
//
//     { "likelihood_test": { "slot_count": 20, "match_threshold_m": 0.4 },
//       "validation": { "min_match_ratio": 0.2 } }

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/refinement/refiner.hpp"
#include "scanloc/session/session.hpp"

namespace scanloc {

struct Config {
  ScoringOptions scoring;           // likelihood_test, likelihood_distance, point_simulation
  ValidationOptions validation;     // validation
  PointMapOptions point_map;        // point_map
  double line_sampling_m = 0.0075;  // spacing when a line map is sampled to points (§3.2.2)
  LaserMounting mounting;           // mounting: {"x_m", "y_m", "yaw_rad"} of the laser on the robot
  RefinerOptions refiner;  // refinement: {"method", "ceres": {...}, "error_descent": {...}}
  SessionOptions session;  // session

  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// Overlays the keys of a JSON object onto `config`; throws std::runtime_error naming the key path
// for unknown keys or values of the wrong type.
void ApplyJson(const nlohmann::json& json, Config& config);
// Reads a JSON config file on top of the defaults; errors name the file.
Config LoadConfig(const std::string& path);
nlohmann::json ToJson(const Config& config);

}  // namespace scanloc
