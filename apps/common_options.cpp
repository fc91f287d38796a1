#include "common_options.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "scanloc/maps/point_map_io.hpp"

namespace scanloc::app {

void MapArguments::Register(CLI::App& command) {
  command.add_option("--map", line_map_path, "line map: 'x1 y1 x2 y2' per line")
      ->check(CLI::ExistingFile);
  command.add_option("--point-map", point_map_path, "point map (PCD)")->check(CLI::ExistingFile);
  command.add_flag("--sample-lines", sample_lines,
                   "use the line map sampled to points (line_sampling_m) instead of its segments");
}

MapView LoadedMaps::View() const {
  MapView view;
  if (!lines.empty()) view.lines = &lines;
  if (points) view.points = points.get();
  return view;
}

LoadedMaps LoadMaps(const MapArguments& arguments, const Config& config, bool required) {
  if (required && arguments.line_map_path.empty() && arguments.point_map_path.empty())
    throw std::runtime_error("a map is required: --map LINES and/or --point-map PCD");
  LoadedMaps maps;
  if (!arguments.point_map_path.empty())
    maps.points =
        std::make_unique<PointMap>(LoadPointMapPcd(arguments.point_map_path, config.point_map));
  if (!arguments.line_map_path.empty()) {
    LineMap lines = ReadLineMap(arguments.line_map_path);
    if (arguments.sample_lines) {
      if (!maps.points) maps.points = std::make_unique<PointMap>(config.point_map);
      const auto samples = SampleLineMap(lines, config.line_sampling_m);
      maps.points->Insert(samples, std::vector<double>(samples.size(), config.line_sampling_m));
    } else {
      maps.lines = std::move(lines);
    }
  }
  return maps;
}

void ConfigArguments::Register(CLI::App& command) {
  command.add_option("--config", config_path, "configuration file (JSON)")
      ->check(CLI::ExistingFile);
  command.add_option("--set", sets,
                     "override one option: section.key=value, e.g. likelihood_test.slot_count=30 "
                     "(`scanloc options` lists every key)");
  command.add_option("--min-match-ratio", min_match_ratio, "rule 1 MinMatchRatio (default 0.3)");
  command.add_option("--match-threshold", match_threshold_m, "T_Map in metres (default 0.5)");
}

Config ConfigArguments::Build() const {
  Config config = config_path.empty() ? Config{} : LoadConfig(config_path);
  for (const auto& assignment : sets) {
    const auto equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0)
      throw std::runtime_error("--set " + assignment + ": expected section.key=value");
    nlohmann::json value;
    const std::string text = assignment.substr(equals + 1);
    try {
      value = nlohmann::json::parse(text);
    } catch (const nlohmann::json::out_of_range& e) {  // a number beyond a double: 1e400
      throw std::runtime_error("--set " + assignment + ": " + e.what());
    } catch (const nlohmann::json::exception&) {
      value = text;  // a bare word, e.g. kernel=huber
    }
    nlohmann::json patch = value;
    std::string path = assignment.substr(0, equals);
    for (auto dot = path.rfind('.');; dot = path.rfind('.')) {
      const std::string key = dot == std::string::npos ? path : path.substr(dot + 1);
      patch = nlohmann::json{{key, patch}};
      if (dot == std::string::npos) break;
      path.resize(dot);
    }
    try {
      ApplyJson(patch, config);
    } catch (const std::exception& e) {
      throw std::runtime_error("--set " + assignment + ": " + e.what());
    }
  }
  if (min_match_ratio) config.validation.min_match_ratio = *min_match_ratio;
  if (match_threshold_m) config.scoring.test.match_threshold_m = *match_threshold_m;
  try {
    config.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("invalid option (--config, --set or a flag): ") +
                             e.what());
  }
  return config;
}

}  // namespace scanloc::app
