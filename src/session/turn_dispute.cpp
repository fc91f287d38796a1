#include "scanloc/session/turn_dispute.hpp"

#include <cmath>

namespace scanloc {

std::optional<TurnDispute> DisputedTurn(const Pose2D& prediction, const Pose2D& tracked,
                                        const ClosureAttempt& closure, double min_correction_rad,
                                        double agree_rad) {
  if (!closure.pending || closure.accepted) return std::nullopt;
  TurnDispute dispute;
  dispute.T_world_robot_tracked = tracked;
  dispute.correction_rad = NormalizeAngle(tracked.yaw_rad - prediction.yaw_rad);
  // Where the closure puts the scan in the session's frame: its match less the correction of the
  // run before it (how the old nodes' frame has drifted from the newest nodes'), when there was
  // one.
  const Pose2D implied = closure.run_correction
                             ? closure.run_correction->Inverse() * closure.T_world_robot_matched
                             : closure.T_world_robot_matched;
  const double matched = implied.yaw_rad;
  dispute.closure_from_prediction_rad = NormalizeAngle(matched - prediction.yaw_rad);
  dispute.closure_from_tracked_rad = NormalizeAngle(matched - tracked.yaw_rad);
  if (std::abs(dispute.correction_rad) <= min_correction_rad ||
      std::abs(dispute.closure_from_prediction_rad) > agree_rad ||
      std::abs(dispute.closure_from_tracked_rad) <= agree_rad)
    return std::nullopt;
  return dispute;
}

}  // namespace scanloc
