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

// Does a closure know better than the session? The closures beside the relative postures a
// trajectory (the session's own, as it gave them online) holds between the same two scans, both
// scored on the same reference poses.
struct ClosuresBesideTrajectory {
  std::vector<std::size_t> compared;  // the closures whose two scans the trajectory has, in order
  std::size_t not_in_trajectory = 0;  // the others
  ClosurePrecision closures;          // the compared closures, scored
  ClosurePrecision trajectory;        // the trajectory's relative postures of the same scans
  // Per compared closure: how far it moved its scan from where the trajectory put it, seen from
  // the old scan (the translation of closure ⊖ trajectory), metres.
  std::vector<double> disagreement_m;
};

// Same errors as EvaluateClosures.
ClosuresBesideTrajectory CompareWithTrajectory(const std::vector<ClosureMeasurement>& closures,
                                               const std::vector<StampedPose>& reference,
                                               const std::vector<StampedPose>& trajectory,
                                               const ClosurePrecisionOptions& options = {});

// The compared closures with reference poses, grouped by their disagreement with the trajectory:
// bin k holds [edges_m[k-1], edges_m[k]) (bin 0 from 0, the last one open).
struct DisagreementBin {
  double from_m = 0.0;
  double to_m = 0.0;                 // infinity for the last bin
  std::size_t closures = 0;          // with reference poses for both scans
  std::size_t closure_right = 0;     // the closure within the bounds
  std::size_t trajectory_right = 0;  // the trajectory's relative posture within the bounds
};

// Throws std::invalid_argument unless edges_m is finite, positive and increasing.
std::vector<DisagreementBin> RightByDisagreement(const ClosuresBesideTrajectory& comparison,
                                                 const std::vector<double>& edges_m);

}  // namespace scanloc
