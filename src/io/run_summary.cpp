#include "scanloc/io/run_summary.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace scanloc {
namespace {

// The parsed file, or nothing when it does not exist; nlohmann::json::exception when it is not
// JSON (the callers say what they expected).
std::optional<nlohmann::json> ParseIfPresent(const std::string& summary_path) {
  if (!std::filesystem::exists(summary_path)) return std::nullopt;
  std::ifstream in(summary_path);
  if (!in) throw std::runtime_error("cannot open " + summary_path);
  return nlohmann::json::parse(in);
}

}  // namespace

std::optional<LaserMounting> ReadRunMounting(const std::string& summary_path) {
  try {
    const std::optional<nlohmann::json> read = ParseIfPresent(summary_path);
    if (!read) return std::nullopt;
    const nlohmann::json& summary = *read;
    if (!summary.contains("config") || !summary["config"].contains("mounting")) return std::nullopt;
    const nlohmann::json& m = summary["config"]["mounting"];
    const Pose2D pose(m.at("x_m").get<double>(), m.at("y_m").get<double>(),
                      m.at("yaw_rad").get<double>());
    if (!std::isfinite(pose.x_m) || !std::isfinite(pose.y_m) || !std::isfinite(pose.yaw_rad))
      throw std::runtime_error(summary_path + ": config.mounting must be finite");
    return LaserMounting{pose};
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(
        summary_path + ": expected JSON with config.mounting {x_m, y_m, yaw_rad}: " + e.what());
  }
}

std::optional<double> ReadMapSignatureBound(const std::string& summary_path) {
  try {
    const std::optional<nlohmann::json> summary = ParseIfPresent(summary_path);
    if (!summary || !summary->contains("map_signature")) return std::nullopt;
    const nlohmann::json& signature = (*summary)["map_signature"];
    if (!signature.at("learned").get<bool>()) return std::nullopt;
    const double bound = signature.at("max_expect_value_m").get<double>();
    if (!(bound > 0.0) || !std::isfinite(bound))
      throw std::runtime_error(summary_path + ": map_signature.max_expect_value_m must be > 0");
    return bound;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(
        summary_path +
        ": expected JSON with map_signature {learned, max_expect_value_m}: " + e.what());
  }
}

}  // namespace scanloc
