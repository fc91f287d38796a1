// scanloc export-grid: an occupancy grid (map_server's map.pgm + map.yaml) from a session's run
// folder, casting the logged scans at the postures the session kept.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>

#include "commands.hpp"
#include "scanloc/io/occupancy_grid_io.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc::app {
namespace {

// Without the log, the grid is cast from scans simulated from the point map: one beam per 0.5°
// over a full turn, out to 30 m.
constexpr std::size_t kSimulatedBeams = 720;
constexpr double kSimulatedRangeM = 30.0;

nlohmann::json ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": expected JSON: " + e.what());
  }
}

// The timestamps of the iterations that were validated (or the first), from iterations.jsonl.
std::set<double> MapScanStamps(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::set<double> stamps;
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      const auto record = nlohmann::json::parse(text);
      if (record.value("validated", false) || record.value("first", false))
        stamps.insert(record.at("timestamp_s").get<double>());
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(path + ":" + std::to_string(line) +
                               ": expected an iteration record with timestamp_s: " + e.what());
    }
  }
  return stamps;
}

std::vector<StampedPose> MapScanPoses(const std::vector<StampedPose>& trajectory,
                                      const std::set<double>& stamps) {
  std::vector<StampedPose> kept;
  for (const StampedPose& pose : trajectory) {
    const auto it = stamps.lower_bound(pose.timestamp_s - 1e-4);
    if (it != stamps.end() && std::abs(*it - pose.timestamp_s) <= 1e-4) kept.push_back(pose);
  }
  return kept;
}

struct ExportGridArguments {
  std::string run_dir, log_path, out_dir, name = "map";
  double resolution_m = 0.05;
  bool all_scans = false;
};

void ExportGrid(const ExportGridArguments& a) {
  const std::string run = a.run_dir;
  const nlohmann::json summary = ReadJsonFile(run + "/summary.json");
  std::string log = a.log_path;
  if (log.empty()) {
    const auto inputs = summary.value("inputs", nlohmann::json::object());
    if (inputs.contains("log") && inputs["log"].is_string()) log = inputs["log"];
  }
  const bool have_log = !log.empty() && std::filesystem::exists(log);
  if (!have_log && !std::filesystem::exists(run + "/map.pcd"))
    throw std::runtime_error(run + "/summary.json: the session's log " +
                             (log.empty() ? std::string("is not named") : log + " is absent") +
                             " and there is no map.pcd; give the log with --log");
  LaserMounting mounting;
  if (summary.contains("config") && summary["config"].contains("mounting")) {
    const auto& m = summary["config"]["mounting"];
    mounting.T_robot_laser =
        Pose2D(m.value("x_m", 0.0), m.value("y_m", 0.0), m.value("yaw_rad", 0.0));
  }
  std::vector<StampedPose> poses = ReadTumTrajectory(run + "/trajectory.tum");
  if (!a.all_scans) poses = MapScanPoses(poses, MapScanStamps(run + "/iterations.jsonl"));
  OccupancyGridOptions options;
  options.resolution_m = a.resolution_m;
  GridFromLogResult built;
  if (have_log) {
    built = BuildGridFromLog(log, poses, mounting, options);
  } else {
    std::cout << "export-grid: no log (" << (log.empty() ? "none named" : log)
              << "): scans simulated from map.pcd at the session's postures\n";
    const PointMap map = LoadPointMapPcd(run + "/map.pcd");
    built = BuildGridFromPointMap(
        map, poses, mounting, MakeLayout(kSimulatedBeams, 2.0 * M_PI, kSimulatedRangeM), options);
  }
  if (built.scans_used == 0)
    throw std::runtime_error("no scan of " + log + " has a posture in " + run +
                             "/trajectory.tum (is it the session's log?)");
  const std::string out = a.out_dir.empty() ? run : a.out_dir;
  std::filesystem::create_directories(out);
  const OccupancyGridFiles files = WriteOccupancyGrid(out, built.grid, a.name);
  std::cout << "export-grid: " << built.scans_used << " of " << built.scans_read << " scans, "
            << built.grid.width << " × " << built.grid.height << " cells of "
            << built.grid.resolution_m << " m\nwrote " << files.image_path << ", "
            << files.yaml_path << "\n";
}

}  // namespace

void RegisterExportGridCommand(CLI::App& app) {
  auto a = std::make_shared<ExportGridArguments>();
  CLI::App* command = app.add_subcommand(
      "export-grid",
      "occupancy grid (map_server's map.pgm + map.yaml) from a session's run folder");
  command->add_option("RUN_DIR", a->run_dir, "run folder of `scanloc session`")
      ->required()
      ->check(CLI::ExistingDirectory);
  command
      ->add_option("--log", a->log_path, "the session's log (default: summary.json's inputs.log)")
      ->check(CLI::ExistingFile);
  command->add_option("--resolution", a->resolution_m, "cell side in metres")
      ->check(CLI::PositiveNumber);
  command->add_option("--out", a->out_dir,
                      "folder to write map.pgm and map.yaml (default RUN_DIR)");
  command->add_option("--name", a->name, "file name without extension");
  command->add_flag("--all-scans", a->all_scans,
                    "cast every localised scan, not only the validated ones");
  command->final_callback([a] { ExportGrid(*a); });
}

}  // namespace scanloc::app
