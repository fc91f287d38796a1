#include "scanloc/io/run_grid.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "scanloc/io/run_summary.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc {
namespace {

// Without the log, the grid is cast from scans simulated from the point map: one beam per 0.5°
// over a full turn, out to 30 m.
constexpr std::size_t kSimulatedBeams = 720;
constexpr double kSimulatedRangeM = 30.0;
// TUM trajectories keep microseconds; a record's posture is the one within this of its stamp.
constexpr double kStampToleranceS = 1e-4;

nlohmann::json ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": expected JSON: " + e.what());
  }
}

// The timestamps of the iterations CastIntoGrid picks, from iterations.jsonl.
std::set<double> GridScanStamps(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::set<double> stamps;
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      const auto record = nlohmann::json::parse(text);
      if (CastIntoGrid(record.value("validated", false), record.value("first", false)))
        stamps.insert(record.at("timestamp_s").get<double>());
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(path + ":" + std::to_string(line) +
                               ": expected an iteration record with timestamp_s: " + e.what());
    }
  }
  return stamps;
}

std::vector<StampedPose> PosesAt(const std::vector<StampedPose>& trajectory,
                                 const std::set<double>& stamps) {
  std::vector<StampedPose> kept;
  for (const StampedPose& pose : trajectory) {
    const auto it = stamps.lower_bound(pose.timestamp_s - kStampToleranceS);
    if (it != stamps.end() && std::abs(*it - pose.timestamp_s) <= kStampToleranceS)
      kept.push_back(pose);
  }
  return kept;
}

}  // namespace

RunGrid BuildRunFolderGrid(const RunGridRequest& request) {
  const std::string& run = request.run_dir;
  const nlohmann::json summary = ReadJsonFile(run + "/summary.json");
  RunGrid result;
  std::string log = request.log_path;
  if (log.empty()) {
    const auto inputs = summary.value("inputs", nlohmann::json::object());
    if (inputs.contains("log") && inputs["log"].is_string()) log = inputs["log"];
  }
  const bool have_log = !log.empty() && std::filesystem::exists(log);
  if (!have_log && !std::filesystem::exists(run + "/map.pcd"))
    throw std::runtime_error(run + "/summary.json: the session's log " +
                             (log.empty() ? std::string("is not named") : log + " is absent") +
                             " and there is no map.pcd; give the log with --log");
  const LaserMounting mounting = ReadRunMounting(run + "/summary.json").value_or(LaserMounting{});
  std::vector<StampedPose> poses = ReadTumTrajectory(run + "/trajectory.tum");
  if (!request.all_scans) poses = PosesAt(poses, GridScanStamps(run + "/iterations.jsonl"));
  if (have_log) {
    result.log_path = log;
    result.built = BuildGridFromLog(log, poses, mounting, request.options);
  } else {
    result.simulated_from_map = true;
    const PointMap map = LoadPointMapPcd(run + "/map.pcd");
    result.built = BuildGridFromPointMap(map, poses, mounting,
                                         MakeLayout(kSimulatedBeams, 2.0 * M_PI, kSimulatedRangeM),
                                         request.options);
  }
  if (result.built.scans_used == 0)
    throw std::runtime_error("no scan of " + log + " has a posture in " + run +
                             "/trajectory.tum (is it the session's log?)");
  return result;
}

}  // namespace scanloc
