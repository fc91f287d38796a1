#include "evaluation_frame.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "scanloc/io/run_summary.hpp"

namespace scanloc::app {

EvaluationFrame ResolveEvaluationFrame(const std::vector<double>& given,
                                       const std::string& run_folder) {
  if (given.size() == 3) {
    if (!std::isfinite(given[0]) || !std::isfinite(given[1]) || !std::isfinite(given[2]))
      throw std::runtime_error("--mounting: expected three finite numbers, X Y (m) and YAW (rad)");
    return {LaserMounting{Pose2D(given[0], given[1], given[2])}, "given with --mounting"};
  }
  const std::string summary = (std::filesystem::path(run_folder) / "summary.json").string();
  if (const std::optional<LaserMounting> mounting = ReadRunMounting(summary))
    return {*mounting, "from " + summary};
  std::cerr << "note: " << summary
            << " records no laser mounting: the postures are scored as the scans' own (give "
               "--mounting X Y YAW if they are the robot's)\n";
  return {LaserMounting{}, "none known"};
}

std::string Describe(const EvaluationFrame& frame) {
  const Pose2D& m = frame.mounting.T_robot_laser;
  char text[128];
  std::snprintf(text, sizeof text, "laser at (%.3f, %.3f) m, %.3f rad on the robot", m.x_m, m.y_m,
                m.yaw_rad);
  return std::string(text) + ", " + frame.source;
}

nlohmann::json ToJson(const EvaluationFrame& frame) {
  const Pose2D& m = frame.mounting.T_robot_laser;
  return {{"x_m", m.x_m}, {"y_m", m.y_m}, {"yaw_rad", m.yaw_rad}, {"source", frame.source}};
}

}  // namespace scanloc::app
