#pragma once
// Resuming a session: what one recorded iteration says that the session needs to stand where it
// stood after it, without localising the scan again (the expensive part). The session replays the
// scan with the recorded decision (posture, confirmation, the kept refinement's test and
// covariance), extends its map and tries its loop closures as it did then, and checks that what
// it recomputes agrees with the record: a run folder resumed with another log, configuration or
// version of scanloc is refused rather than continued into a mix.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/likelihood/likelihood_test.hpp"

namespace scanloc {

struct IterationRecord;

struct RecordedIteration {
  std::size_t index = 0;
  double timestamp_s = 0.0;
  bool skipped = false;    // not localised: the robot had not moved enough
  bool first = false;      // the first iteration of a session without a prior map
  bool localised = false;  // candidates were evaluated and refined
  Pose2D T_world_robot;    // the posture kept
  bool validated = false;
  Verdict verdict = Verdict::kValid;
  // The kept refinement's Likelihood Test and covariance, when the scan was localised.
  std::optional<LikelihoodTestResult> kept_test;
  std::optional<Eigen::Matrix3d> kept_covariance;
  double signature_expect_value_m = 0.0;
  // The refinement the correction gate refused (correction_gate.hpp), when it refused one.
  std::optional<Pose2D> refused;
  // The refinement refused as adding up to a slide (correction_drift.hpp), when one was.
  std::optional<Pose2D> slide_refused;
  // The tracker's posture a closure's dispute withdrew (turn_dispute.hpp), when one did.
  std::optional<Pose2D> disputed;
  // The refinement the rules ranked first where the session kept a tighter one
  // (tighter_refinement.hpp): its index among the refinements, or -1.
  int outranked_refinement = -1;
  bool searched = false, lost = false, recovered = false;
  bool inserted = false;
  bool new_ground = false;  // extended the map on new ground (new_ground.hpp)
  std::size_t carved = 0, map_points = 0;
  bool closure_tried = false, closure_accepted = false, closure_rendered = false;
};

// A replayed iteration that does not agree with its record.
class ReplayMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What differs between a replayed iteration and its record ("" when they agree): the first field
// that does, with both values.
std::string DescribeReplayMismatch(const IterationRecord& replayed,
                                   const RecordedIteration& recorded);

}  // namespace scanloc
