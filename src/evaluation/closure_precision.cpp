#include "scanloc/evaluation/closure_precision.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace scanloc {
namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

bool Positive(double value) {
  return std::isfinite(value) && value > 0.0;
}

bool Within(const Pose2D& error, const ClosurePrecisionOptions& options) {
  return error.Translation().norm() <= options.max_translation_error_m &&
         std::abs(NormalizeAngle(error.yaw_rad)) * kDegreesPerRadian <=
             options.max_rotation_error_deg;
}

// The closures `chosen` selects, scored.
template <class Choose>
ClosureTally Tally(const std::vector<ClosureMeasurement>& closures,
                   const std::vector<StampedPose>& reference,
                   const ClosurePrecisionOptions& options, const Choose& chosen) {
  std::vector<Relation> relations;
  for (const ClosureMeasurement& closure : closures)
    if (chosen(closure)) relations.push_back({closure.t_old_s, closure.t_s, closure.T_old_robot});
  ClosureTally tally;
  tally.closures = relations.size();
  RelationsEvaluationOptions relation_options;
  relation_options.timestamp_tolerance_s = options.timestamp_tolerance_s;
  tally.evaluation = EvaluateRelations(reference, relations, relation_options);
  for (const Pose2D& error : tally.evaluation.errors) tally.right += Within(error, options) ? 1 : 0;
  return tally;
}

}  // namespace

ClosurePrecision EvaluateClosures(const std::vector<ClosureMeasurement>& closures,
                                  const std::vector<StampedPose>& reference,
                                  const ClosurePrecisionOptions& options) {
  if (!Positive(options.max_translation_error_m) || !Positive(options.max_rotation_error_deg))
    throw std::invalid_argument("EvaluateClosures: the error bounds must be finite and positive");
  ClosurePrecision precision;
  precision.measured = Tally(closures, reference, options, [](const auto&) { return true; });
  precision.accepted =
      Tally(closures, reference, options, [](const auto& c) { return c.accepted; });
  precision.in_graph =
      Tally(closures, reference, options, [](const auto& c) { return c.in_graph; });
  precision.errors.resize(closures.size());
  precision.right.resize(closures.size(), false);
  const RelationsEvaluation& all = precision.measured.evaluation;
  for (std::size_t k = 0; k < all.errors.size(); ++k) {
    precision.errors[all.matched_relations[k]] = all.errors[k];
    precision.right[all.matched_relations[k]] = Within(all.errors[k], options);
  }
  return precision;
}

ClosuresBesideTrajectory CompareWithTrajectory(const std::vector<ClosureMeasurement>& closures,
                                               const std::vector<StampedPose>& reference,
                                               const std::vector<StampedPose>& trajectory,
                                               const ClosurePrecisionOptions& options) {
  std::vector<std::pair<double, double>> pairs;
  for (const ClosureMeasurement& closure : closures)
    pairs.push_back({closure.t_old_s, closure.t_s});
  RelationsEvaluationOptions lookup;
  lookup.timestamp_tolerance_s = options.timestamp_tolerance_s;
  const std::vector<std::optional<Pose2D>> placed = RelativePoses(trajectory, pairs, lookup);
  ClosuresBesideTrajectory comparison;
  std::vector<ClosureMeasurement> compared, by_trajectory;
  for (std::size_t i = 0; i < closures.size(); ++i) {
    if (!placed[i]) {
      ++comparison.not_in_trajectory;
      continue;
    }
    comparison.compared.push_back(i);
    compared.push_back(closures[i]);
    by_trajectory.push_back(closures[i]);
    by_trajectory.back().T_old_robot = *placed[i];
    comparison.disagreement_m.push_back(
        Between(*placed[i], closures[i].T_old_robot).Translation().norm());
  }
  comparison.closures = EvaluateClosures(compared, reference, options);
  comparison.trajectory = EvaluateClosures(by_trajectory, reference, options);
  return comparison;
}

std::vector<DisagreementBin> RightByDisagreement(const ClosuresBesideTrajectory& comparison,
                                                 const std::vector<double>& edges_m) {
  for (std::size_t k = 0; k < edges_m.size(); ++k)
    if (!Positive(edges_m[k]) || (k > 0 && !(edges_m[k] > edges_m[k - 1])))
      throw std::invalid_argument(
          "RightByDisagreement: the bin edges must be finite, positive and increasing");
  std::vector<DisagreementBin> bins(edges_m.size() + 1);
  for (std::size_t k = 0; k < bins.size(); ++k) {
    bins[k].from_m = k == 0 ? 0.0 : edges_m[k - 1];
    bins[k].to_m = k < edges_m.size() ? edges_m[k] : std::numeric_limits<double>::infinity();
  }
  const ClosurePrecision& closures = comparison.closures;
  const ClosurePrecision& trajectory = comparison.trajectory;
  for (std::size_t i = 0; i < comparison.disagreement_m.size(); ++i) {
    if (!closures.errors[i]) continue;
    const auto edge =
        std::upper_bound(edges_m.begin(), edges_m.end(), comparison.disagreement_m[i]);
    DisagreementBin& bin = bins[static_cast<std::size_t>(edge - edges_m.begin())];
    ++bin.closures;
    bin.closure_right += closures.right[i] ? 1 : 0;
    bin.trajectory_right += trajectory.right[i] ? 1 : 0;
  }
  return bins;
}

}  // namespace scanloc
