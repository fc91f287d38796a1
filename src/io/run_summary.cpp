#include "scanloc/io/run_summary.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

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

namespace {

// map_signature.samples: [x_m, y_m, expect_value_m] each, finite, the EV >= 0 (none in a summary
// written before the samples were kept).
std::vector<MapSignatureSample> ReadSamples(const nlohmann::json& signature,
                                            const std::string& summary_path) {
  std::vector<MapSignatureSample> samples;
  if (!signature.contains("samples")) return samples;
  std::size_t i = 0;
  for (const nlohmann::json& s : signature.at("samples")) {
    const MapSignatureSample sample{s.at(0).get<double>(), s.at(1).get<double>(),
                                    s.at(2).get<double>()};
    if (s.size() != 3 || !std::isfinite(sample.x_m) || !std::isfinite(sample.y_m) ||
        !std::isfinite(sample.expect_value_m) || sample.expect_value_m < 0.0)
      throw std::runtime_error(summary_path + ": map_signature.samples[" + std::to_string(i) +
                               "] must be [x_m, y_m, expect_value_m >= 0], finite");
    samples.push_back(sample);
    ++i;
  }
  return samples;
}

}  // namespace

std::optional<MapSignature> ReadMapSignature(const std::string& summary_path) {
  try {
    const std::optional<nlohmann::json> summary = ParseIfPresent(summary_path);
    if (!summary || !summary->contains("map_signature")) return std::nullopt;
    const nlohmann::json& signature = (*summary)["map_signature"];
    if (!signature.at("learned").get<bool>()) return std::nullopt;
    MapSignature read;
    read.learned = true;
    read.max_expect_value_m = signature.at("max_expect_value_m").get<double>();
    if (!(read.max_expect_value_m > 0.0) || !std::isfinite(read.max_expect_value_m))
      throw std::runtime_error(summary_path + ": map_signature.max_expect_value_m must be > 0");
    read.median_expect_value_m = signature.value("median_expect_value_m", 0.0);
    if (!std::isfinite(read.median_expect_value_m) || read.median_expect_value_m < 0.0)
      throw std::runtime_error(summary_path +
                               ": map_signature.median_expect_value_m must be >= 0");
    read.scans = signature.value("scans", std::size_t{0});
    read.samples = ReadSamples(signature, summary_path);
    return read;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(summary_path +
                             ": expected JSON with map_signature {learned, max_expect_value_m, "
                             "median_expect_value_m, samples [[x_m, y_m, expect_value_m]...]}: " +
                             e.what());
  }
}

}  // namespace scanloc
