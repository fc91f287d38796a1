#include "scanloc/report/run_contents.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "scanloc/common/parse_error.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// summary.json, or {} with a note when it is missing (a session killed before it finished).
json ReadSummary(const std::string& path, std::vector<std::string>& notes) {
  if (!fs::exists(path)) {
    notes.push_back(
        "summary.json is missing (did the session finish?): the inputs and the "
        "configuration are unknown, defaults are used");
    return json::object();
  }
  const std::string text = ReadText(path);
  try {
    json summary = json::parse(text);
    if (!summary.is_object()) throw ParseError(path, 1, "expected a JSON object");
    return summary;
  } catch (const json::parse_error& e) {
    const std::size_t end = std::min<std::size_t>(e.byte, text.size());
    const std::size_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
    throw ParseError(path, line, std::string("expected JSON: ") + e.what());
  }
}

// The string at summary[section][key] (or summary[key] when section is empty), or "".
std::string SummaryString(const json& summary, const char* section, const char* key) {
  const json* object = &summary;
  if (section) {
    const auto it = summary.find(section);
    if (it == summary.end() || !it->is_object()) return "";
    object = &*it;
  }
  const auto it = object->find(key);
  return it != object->end() && it->is_string() ? it->get<std::string>() : "";
}

// A run folder's configuration as the current keys spell it: runs written before E_max had one
// key kept the session's own as session.max_expect_value_m, which is what its rule 2 applied.
json WithoutMovedKeys(json config) {
  if (!config.is_object() || !config.contains("session") || !config["session"].is_object())
    return config;
  json& session = config["session"];
  if (const auto it = session.find("max_expect_value_m"); it != session.end()) {
    config["validation"]["max_expect_value_m"] = *it;
    session.erase(it);
  }
  return config;
}

// The first candidate that exists as a file, or "".
std::string FirstExisting(const std::vector<std::string>& candidates) {
  for (const std::string& path : candidates)
    if (!path.empty() && fs::is_regular_file(path)) return path;
  return "";
}

// The session's occupancy grid (map.yaml + map.pgm); none for runs written before sessions wrote
// one, or when it cannot be read (said in `notes`).
std::optional<OccupancyGridImage> ReadGrid(const std::string& directory,
                                           std::vector<std::string>& notes) {
  const std::string yaml_path = directory + "/map.yaml";
  if (!std::filesystem::exists(yaml_path)) {
    notes.push_back("the run folder has no occupancy grid (map.yaml): `scanloc export-grid " +
                    directory + "` writes one, over which the page then draws the trajectory");
    return std::nullopt;
  }
  try {
    return ReadOccupancyGridImage(yaml_path);
  } catch (const std::exception& e) {
    notes.push_back(std::string("the occupancy grid could not be read (") + e.what() +
                    "): the trajectory is drawn over map.pcd's points");
    return std::nullopt;
  }
}

}  // namespace

RunContents ReadRunContents(const std::string& directory, const RunInputOverrides& overrides) {
  if (!fs::is_directory(directory))
    throw std::runtime_error("no run folder at " + directory +
                             " (expected what `scanloc session --out DIR` writes)");
  RunContents run;
  run.directory = directory;
  const std::string iterations_path = directory + "/iterations.jsonl";
  if (!fs::exists(iterations_path))
    throw std::runtime_error(iterations_path + " is missing: is " + directory +
                             " a session's run folder?");
  run.iterations = ReadIterationRows(iterations_path);
  if (run.iterations.truncated_last_line)
    run.notes.push_back(
        "the last line of iterations.jsonl is incomplete (the session was "
        "stopped while writing it) and is left out");

  run.summary = ReadSummary(directory + "/summary.json", run.notes);
  if (const auto it = run.summary.find("config"); it != run.summary.end()) {
    try {
      ApplyJson(WithoutMovedKeys(*it), run.config);
    } catch (const std::exception& e) {
      run.config = Config{};
      run.notes.push_back(std::string("the configuration in summary.json could not be read (") +
                          e.what() + "): defaults are used for the figures' thresholds");
    }
  }

  run.grid = ReadGrid(directory, run.notes);
  const std::string map_path = directory + "/map.pcd";
  if (!fs::exists(map_path)) {
    run.notes.push_back("map.pcd is missing: the figures show no final map");
  } else {
    try {
      const PointMap map = LoadPointMapPcd(map_path, run.config.point_map);
      run.final_map.reserve(map.size());
      for (std::size_t i = 0; i < map.size(); ++i) run.final_map.push_back(map.point(i));
    } catch (const std::exception& e) {
      run.notes.push_back(std::string("map.pcd could not be read: ") + e.what());
    }
  }

  // The inputs: the command line's, else the absolute paths the session recorded, else the
  // path as the session was given it (relative to where it ran).
  const std::string log_named = !overrides.log_path.empty()
                                    ? overrides.log_path
                                    : SummaryString(run.summary, "inputs", "log");
  run.log_path = FirstExisting({log_named, SummaryString(run.summary, nullptr, "log")});
  if (run.log_path.empty()) {
    const std::string named =
        !log_named.empty() ? log_named : SummaryString(run.summary, nullptr, "log");
    run.notes.push_back(named.empty() ? "the run does not name its sequence: the scans are "
                                        "unavailable (give it with --log)"
                                      : "the sequence " + named +
                                            " is not there: the scans are unavailable (give it "
                                            "with --log)");
  }
  const std::string line_map_named = !overrides.line_map_path.empty()
                                         ? overrides.line_map_path
                                         : SummaryString(run.summary, "inputs", "line_map");
  if (!line_map_named.empty()) {
    if (!fs::is_regular_file(line_map_named)) {
      run.notes.push_back("the line map " + line_map_named +
                          " is not there: the figures show no line map");
    } else {
      try {
        run.line_map = ReadLineMap(line_map_named);
      } catch (const std::exception& e) {
        run.notes.push_back(std::string("the line map could not be read: ") + e.what());
      }
    }
  }
  const std::string point_map_named = SummaryString(run.summary, "inputs", "point_map");
  run.point_map_path = FirstExisting({point_map_named});
  if (!point_map_named.empty() && run.point_map_path.empty())
    run.notes.push_back("the initial point map " + point_map_named +
                        " is not there: the maps rebuilt for the figures start empty");
  return run;
}

}  // namespace scanloc
