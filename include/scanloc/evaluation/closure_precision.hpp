#pragma once
// How many of a session's loop closures were right: each closure's measurement (the scan seen
// from the old scan it closed with) scored against reference poses of the same two scans, with the
// relations metric (Kümmerle et al. 2009), and counted right when within a translation and a
// rotation bound.

#include <cstddef>
#include <optional>
#include <vector>

#include "scanloc/evaluation/relations_evaluation.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/io/trajectory.hpp"

namespace scanloc {

// One closure a session measured.
struct ClosureMeasurement {
  double t_old_s = 0.0;   // the old scan's timestamp
  double t_s = 0.0;       // the closing scan's
  Pose2D T_old_robot;     // the closing scan seen from the old one
  bool accepted = false;  // it confirmed a batch of agreeing closures
  bool in_graph = false;  // its edge is in the session's final graph
};

struct ClosurePrecisionOptions {
  double timestamp_tolerance_s = 1e-3;  // as for EvaluateRelations
  // A closure is right when its error is within both. Metres and degrees, > 0.
  double max_translation_error_m = 0.1;
  double max_rotation_error_deg = 1.0;
};

// One group of closures (all measured, the accepted ones, those in the graph).
struct ClosureTally {
  std::size_t closures = 0;
  std::size_t right = 0;           // of those with reference poses for both scans
  RelationsEvaluation evaluation;  // matched: those with reference poses; their error statistics
};

struct ClosurePrecision {
  // Per measurement, in order: its error δ ⊖ δ*, absent when a scan has no reference pose.
  std::vector<std::optional<Pose2D>> errors;
  std::vector<bool> right;  // per measurement: an error within both bounds
  ClosureTally measured, accepted, in_graph;
};

// Throws std::invalid_argument for a negative or non-finite tolerance or a bound that is not
// finite and positive.
ClosurePrecision EvaluateClosures(const std::vector<ClosureMeasurement>& closures,
                                  const std::vector<StampedPose>& reference,
                                  const ClosurePrecisionOptions& options = {});

}  // namespace scanloc
