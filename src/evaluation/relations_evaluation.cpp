#include "scanloc/evaluation/relations_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>

#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"

namespace scanloc {
namespace {

// t1 t2 x y z roll pitch yaw
constexpr std::size_t kRelationFields = 8;
// The files print z, roll and pitch as 0.000000; anything larger is a 3D relation.
constexpr double kPlanarTolerance = 1e-6;
constexpr double kDegreesPerRadian = 180.0 / M_PI;

// The trajectory's poses ordered by timestamp, searched for the nearest one.
class TimestampIndex {
 public:
  explicit TimestampIndex(const std::vector<StampedPose>& trajectory) : trajectory_(trajectory) {
    order_.resize(trajectory.size());
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = i;
    // Stable, so that which of several equal timestamps is used does not depend on the library.
    std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) {
      return trajectory_[a].timestamp_s < trajectory_[b].timestamp_s;
    });
  }

  // The pose whose timestamp is nearest t, if it lies within the tolerance.
  std::optional<Pose2D> Find(double t_s, double tolerance_s) const {
    const auto after =
        std::lower_bound(order_.begin(), order_.end(), t_s,
                         [&](std::size_t i, double t) { return trajectory_[i].timestamp_s < t; });
    std::optional<std::size_t> best;
    double best_gap_s = tolerance_s;
    if (after != order_.end()) Consider(*after, t_s, best, best_gap_s);
    if (after != order_.begin()) Consider(*std::prev(after), t_s, best, best_gap_s);
    if (!best) return std::nullopt;
    return trajectory_[*best].pose;
  }

 private:
  void Consider(std::size_t i, double t_s, std::optional<std::size_t>& best,
                double& best_gap_s) const {
    const double gap_s = std::abs(trajectory_[i].timestamp_s - t_s);
    if (gap_s <= best_gap_s) {
      best = i;
      best_gap_s = gap_s;
    }
  }

  const std::vector<StampedPose>& trajectory_;
  std::vector<std::size_t> order_;
};

ErrorStatistics Statistics(const std::vector<double>& values) {
  ErrorStatistics statistics;
  if (values.empty()) return statistics;
  double sum = 0.0;
  for (double value : values) {
    sum += value;
    statistics.max = std::max(statistics.max, value);
  }
  statistics.mean = sum / static_cast<double>(values.size());
  // Two passes rather than E[x²] − E[x]², which cancels badly when the spread is small next to
  // the mean.
  double squared_deviations = 0.0;
  for (double value : values)
    squared_deviations += (value - statistics.mean) * (value - statistics.mean);
  statistics.std = std::sqrt(squared_deviations / static_cast<double>(values.size()));
  return statistics;
}

void RequireTolerance(const RelationsEvaluationOptions& options, const char* function) {
  if (!(options.timestamp_tolerance_s >= 0.0) || !std::isfinite(options.timestamp_tolerance_s))
    throw std::invalid_argument(std::string(function) +
                                ": timestamp_tolerance_s must be finite and >= 0");
}

}  // namespace

std::vector<Relation> ReadRelations(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<Relation> relations;
  std::string text;
  for (std::size_t line = 1; ReadBoundedLine(in, text, path, line); ++line) {
    const std::vector<std::string> fields = SplitFields(text, kRelationFields);
    if (fields.empty()) continue;
    if (fields.size() != kRelationFields)
      throw ParseError(
          path, line,
          "expected 8 fields 't1 t2 x y z roll pitch yaw', got " + std::to_string(fields.size()));
    Relation relation;
    relation.t1_s = ParseFiniteDouble(fields[0], path, line, "timestamp t1 in seconds");
    relation.t2_s = ParseFiniteDouble(fields[1], path, line, "timestamp t2 in seconds");
    const double x_m = ParseFiniteDouble(fields[2], path, line, "x in metres");
    const double y_m = ParseFiniteDouble(fields[3], path, line, "y in metres");
    const double z_m = ParseFiniteDouble(fields[4], path, line, "z in metres");
    const double roll_rad = ParseFiniteDouble(fields[5], path, line, "roll in radians");
    const double pitch_rad = ParseFiniteDouble(fields[6], path, line, "pitch in radians");
    const double yaw_rad = ParseFiniteDouble(fields[7], path, line, "yaw in radians");
    if (std::abs(z_m) > kPlanarTolerance || std::abs(roll_rad) > kPlanarTolerance ||
        std::abs(pitch_rad) > kPlanarTolerance)
      throw ParseError(path, line, "expected a planar relation (z, roll and pitch zero)");
    relation.T_1_2 = Pose2D(x_m, y_m, yaw_rad).Normalized();
    relations.push_back(relation);
  }
  if (in.bad()) throw std::runtime_error("error while reading " + path);
  return relations;
}

std::vector<std::optional<Pose2D>> RelativePoses(
    const std::vector<StampedPose>& trajectory, const std::vector<std::pair<double, double>>& pairs,
    const RelationsEvaluationOptions& options) {
  RequireTolerance(options, "RelativePoses");
  const TimestampIndex index(trajectory);
  std::vector<std::optional<Pose2D>> relative;
  relative.reserve(pairs.size());
  for (const auto& [t1_s, t2_s] : pairs) {
    const std::optional<Pose2D> T_w_1 = index.Find(t1_s, options.timestamp_tolerance_s);
    const std::optional<Pose2D> T_w_2 = index.Find(t2_s, options.timestamp_tolerance_s);
    relative.push_back(T_w_1 && T_w_2 ? std::optional<Pose2D>(Between(*T_w_1, *T_w_2))
                                      : std::nullopt);
  }
  return relative;
}

RelationsEvaluation EvaluateRelations(const std::vector<StampedPose>& trajectory,
                                      const std::vector<Relation>& relations,
                                      const RelationsEvaluationOptions& options) {
  RequireTolerance(options, "EvaluateRelations");
  std::vector<std::pair<double, double>> pairs;
  pairs.reserve(relations.size());
  for (const Relation& relation : relations) pairs.emplace_back(relation.t1_s, relation.t2_s);
  const std::vector<std::optional<Pose2D>> estimated = RelativePoses(trajectory, pairs, options);
  RelationsEvaluation evaluation;
  std::vector<double> translations_m, rotations_deg, translations_squared_m2,
      rotations_squared_deg2;
  for (std::size_t r = 0; r < relations.size(); ++r) {
    const Relation& relation = relations[r];
    if (!estimated[r]) {
      evaluation.unmatched_relations.push_back(relation);
      continue;
    }
    // δ ⊖ δ*: the estimated relative motion seen from the true one.
    const Pose2D error = Between(relation.T_1_2, *estimated[r]);
    evaluation.errors.push_back(error);
    evaluation.matched_relations.push_back(r);
    const double translation_m = error.Translation().norm();
    const double rotation_deg = std::abs(NormalizeAngle(error.yaw_rad)) * kDegreesPerRadian;
    translations_m.push_back(translation_m);
    rotations_deg.push_back(rotation_deg);
    translations_squared_m2.push_back(translation_m * translation_m);
    rotations_squared_deg2.push_back(rotation_deg * rotation_deg);
  }
  evaluation.matched = evaluation.errors.size();
  evaluation.unmatched = evaluation.unmatched_relations.size();
  evaluation.translation_m = Statistics(translations_m);
  evaluation.rotation_deg = Statistics(rotations_deg);
  evaluation.translation_squared_m2 = Statistics(translations_squared_m2);
  evaluation.rotation_squared_deg2 = Statistics(rotations_squared_deg2);
  return evaluation;
}

std::vector<StampedPose> LaserPoses(std::vector<StampedPose> robot_poses,
                                    const LaserMounting& mounting) {
  for (StampedPose& pose : robot_poses) pose.pose = mounting.LaserPose(pose.pose);
  return robot_poses;
}

}  // namespace scanloc
