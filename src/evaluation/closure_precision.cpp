#include "scanloc/evaluation/closure_precision.hpp"

#include <cmath>
#include <stdexcept>

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

}  // namespace scanloc
