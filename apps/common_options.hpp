#pragma once
// Options shared by several subcommands: the map to load and the configuration overrides.

#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scanloc/config/config.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc::app {

struct MapArguments {
  std::string line_map_path;   // --map
  std::string point_map_path;  // --point-map
  bool sample_lines = false;   // --sample-lines: use the line map sampled to points
  void Register(CLI::App& command);
};

// The maps a command works on; owns them, hands out a MapView.
struct LoadedMaps {
  LineMap lines;
  std::unique_ptr<PointMap> points;
  MapView View() const;
};
// Throws when `required` and no map was named.
LoadedMaps LoadMaps(const MapArguments& arguments, const Config& config, bool required = true);

struct ConfigArguments {
  std::string config_path;                  // --config FILE (JSON)
  std::vector<std::string> sets;            // --set section.key=value, applied after the file
  std::optional<double> min_match_ratio;    // --min-match-ratio (validation.min_match_ratio)
  std::optional<double> match_threshold_m;  // --match-threshold (likelihood_test.match_threshold_m)
  void Register(CLI::App& command);
  Config Build() const;
};

}  // namespace scanloc::app
