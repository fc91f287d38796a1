#pragma once
// A heading correction the tracker made, disputed by the closure tried at the same scan.
//
// The tracker matches each scan on the map its newest nodes laid. When those few nodes were laid a
// little wrong, a scan can refine onto them turned by most of what the odometry is allowed to err,
// and the rules confirm it: orebro's noisy scan 213 turned 0.108 rad from a prediction that was
// right to 0.005 rad (the correction gate's bound was 0.122 rad), and every relation across it
// was 1 m off. The closure tried at the same scan matches it on older nodes: another map, an
// independent witness. When that match was validated and keeps the prediction's heading while it
// disputes the tracker's, two witnesses stand against one, and the scan takes the prediction, as a
// scan the correction gate refuses does (docs/BENCHMARKS.md, "A turn the closure disputes").

#include <optional>

#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/session/loop_closure.hpp"

namespace scanloc {

struct TurnDispute {
  Pose2D T_world_robot_tracked;  // the tracker's posture, withdrawn
  double correction_rad = 0.0;   // its heading correction of the prediction
  // The closure's heading in the session's frame, less the prediction's and less the tracker's.
  double closure_from_prediction_rad = 0.0;
  double closure_from_tracked_rad = 0.0;
};

// The dispute, when the tracker turned the prediction by more than min_correction_rad and the
// closure tried at the same scan was validated and is pending (an accepted one has moved the graph
// already), its heading within agree_rad of the prediction's and farther than agree_rad from the
// tracker's. The closure's heading is taken in the session's frame: less the correction the
// closures pending before it agreed on, when some did (the old nodes' frame may have turned away
// from the newest nodes'; that drift is no dispute). Headings only: the frames' drift in position
// is larger, while a scan's heading on either map is well pinned.
std::optional<TurnDispute> DisputedTurn(const Pose2D& prediction, const Pose2D& tracked,
                                        const ClosureAttempt& closure, double min_correction_rad,
                                        double agree_rad);

}  // namespace scanloc
