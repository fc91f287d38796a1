#include "scanloc/evaluation/mode_comparison.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/session/session.hpp"

namespace scanloc {
namespace {

// Sums over one run, turned into the result's means at the end.
struct Accumulator {
  double translation_m = 0.0, rotation_rad = 0.0;
  double match_pairs = 0.0, valid_pairs = 0.0, match_ratio = 0.0, expect_value_m = 0.0;
  double time_s = 0.0;
};

// Localises every iteration against a line map that never changes, from the prediction a session
// would make (the previous posture moved by the odometry increment), with the heading candidates
// at every scan: the session's localisation without its gate and without map extension.
class FixedLineMapRun {
 public:
  FixedLineMapRun(const Config& config, LaserMounting mounting, const LineMap& line_map)
      : config_(config), mounting_(mounting), line_map_(line_map), no_points_(config.point_map) {}

  IterationRecord Process(const Iteration& iteration) {
    IterationRecord record;
    record.index = count_++;
    record.timestamp_s = iteration.timestamp_s;
    record.origin = iteration.origin;
    record.prediction = last_pose_ ? *last_pose_ : config_.session.initial_pose;
    if (last_pose_ && last_odometry_ && iteration.odometry)
      record.prediction = *last_pose_ * Between(*last_odometry_, *iteration.odometry);
    const std::vector<Candidate> candidates =
        PredictionCandidates(record.prediction.Normalized(), iteration.external_candidates,
                             /*turning=*/true, mounting_, config_.session);
    const LocalisationOptions options{config_.scoring, config_.validation, config_.refiner};
    record.localisation =
        Localise({&line_map_, &no_points_}, iteration.scan, candidates, mounting_, options,
                 RefinePolicy::kBestValid, config_.session.max_refined_candidates);
    record.T_world_robot = record.Kept()->T_world_robot;
    record.verdict = record.Kept()->verdict;
    record.validated = record.localisation->validated();
    record.total_s = record.localisation->evaluate_s + record.localisation->refine_s;
    last_pose_ = record.T_world_robot;
    if (iteration.odometry) last_odometry_ = iteration.odometry;
    return record;
  }

 private:
  const Config& config_;
  LaserMounting mounting_;
  const LineMap& line_map_;
  const PointMap no_points_;  // the session's point map, which this mode never extends
  std::size_t count_ = 0;
  std::optional<Pose2D> last_pose_, last_odometry_;
};

std::string Millimetres(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", 1000.0 * metres);
  return text;
}

}  // namespace

const char* ToString(MapMode mode) {
  switch (mode) {
    case MapMode::kLineMap:
      return "line map";
    case MapMode::kPointMap:
      return "point map";
    case MapMode::kBoth:
      return "both";
  }
  return "?";
}

MapMode ParseMapMode(const std::string& name) {
  if (name == "lines") return MapMode::kLineMap;
  if (name == "points") return MapMode::kPointMap;
  if (name == "both") return MapMode::kBoth;
  throw std::invalid_argument("unknown map mode '" + name + "': expected lines, points or both");
}

ModeResult RunMode(MapMode mode, const std::string& sequence_path, const LineMap& line_map,
                   const Config& config, std::size_t max_iterations) {
  if (mode != MapMode::kPointMap && line_map.empty())
    throw std::invalid_argument(std::string("map mode '") + ToString(mode) +
                                "' needs a line map with at least one segment");
  SequenceFileSource source(sequence_path);
  Iteration iteration;
  if (!source.Next(iteration)) throw std::runtime_error(sequence_path + ": no iteration");
  Config run_config = config;
  if (source.truth()) run_config.session.initial_pose = *source.truth();

  std::unique_ptr<FixedLineMapRun> fixed;
  std::unique_ptr<Session> session;
  if (mode == MapMode::kLineMap)
    fixed = std::make_unique<FixedLineMapRun>(run_config, source.mounting(), line_map);
  else
    session = std::make_unique<Session>(
        SessionConfig{run_config.session,
                      {run_config.scoring, run_config.validation, run_config.refiner}},
        source.mounting(), mode == MapMode::kBoth ? line_map : LineMap{},
        PointMap(run_config.point_map));

  ModeResult result;
  result.mode = mode;
  Accumulator sum;
  do {
    const IterationRecord record = fixed ? fixed->Process(iteration) : session->Process(iteration);
    ++result.iterations;
    sum.time_s += record.total_s;
    result.map_points = record.map_points;
    if (record.Kept() && !record.skipped) {
      ++result.localised;
      result.validated += record.validated;
      const LikelihoodTestResult& test = record.Kept()->test;
      sum.match_pairs += test.match_pairs;
      sum.valid_pairs += test.valid_pairs;
      sum.match_ratio += test.MatchRatio();
      sum.expect_value_m += test.expect_value_m;
    }
    if (source.truth() && !record.first) {
      const Pose2D error = Between(*source.truth(), record.T_world_robot);
      const double translation = std::hypot(error.x_m, error.y_m);
      const double rotation = std::abs(NormalizeAngle(error.yaw_rad));
      ++result.with_truth;
      sum.translation_m += translation;
      sum.rotation_rad += rotation;
      result.max_translation_error_m = std::max(result.max_translation_error_m, translation);
      result.max_rotation_error_rad = std::max(result.max_rotation_error_rad, rotation);
    }
  } while ((max_iterations == 0 || result.iterations < max_iterations) && source.Next(iteration));

  if (result.with_truth > 0) {
    result.mean_translation_error_m = sum.translation_m / result.with_truth;
    result.mean_rotation_error_rad = sum.rotation_rad / result.with_truth;
  }
  if (result.localised > 0) {
    result.mean_match_pairs = sum.match_pairs / result.localised;
    result.mean_valid_pairs = sum.valid_pairs / result.localised;
    result.mean_match_ratio = sum.match_ratio / result.localised;
    result.mean_expect_value_m = sum.expect_value_m / result.localised;
  }
  result.mean_iteration_s = sum.time_s / result.iterations;
  return result;
}

void PrintComparison(std::ostream& out, const std::vector<ModeResult>& results) {
  char line[256];
  std::snprintf(line, sizeof line, "%-10s %5s %9s %9s  %-23s %-23s %6s %6s %6s %8s %8s\n", "mode",
                "iter.", "localised", "validated", "trans. error mean/max", "rot. error mean/max",
                "MP", "NVP", "MP/NVP", "EV [m]", "ms/iter.");
  out << line;
  for (const ModeResult& r : results) {
    const std::string translation = r.with_truth == 0
                                        ? "n/a"
                                        : Millimetres(r.mean_translation_error_m) + " / " +
                                              Millimetres(r.max_translation_error_m) + " mm";
    char rotation_text[64] = "n/a";
    if (r.with_truth > 0)
      std::snprintf(rotation_text, sizeof rotation_text, "%.1f / %.1f mrad",
                    1000.0 * r.mean_rotation_error_rad, 1000.0 * r.max_rotation_error_rad);
    std::snprintf(line, sizeof line,
                  "%-10s %5zu %9zu %9zu  %-23s %-23s %6.0f %6.0f %6.3f %8.4f %8.1f\n",
                  ToString(r.mode), r.iterations, r.localised, r.validated, translation.c_str(),
                  rotation_text, r.mean_match_pairs, r.mean_valid_pairs, r.mean_match_ratio,
                  r.mean_expect_value_m, 1000.0 * r.mean_iteration_s);
    out << line;
  }
}

}  // namespace scanloc
