#include "scanloc/io/odometry_reversal.hpp"

#include <algorithm>

namespace scanloc {

void OdometryReversalRepair::AddVelocity(double tv_mps) {
  max_velocity_mps_ = velocities_ == 0 ? tv_mps : std::max(max_velocity_mps_, tv_mps);
  ++velocities_;
}

Pose2D OdometryReversalRepair::Repair(const Pose2D& logged) {
  Pose2D repaired = offset_ ? (*offset_ * logged).Normalized() : logged;
  if (logged_previous_ && velocities_ > 0 && max_velocity_mps_ < -kReversingMps) {
    Pose2D step = Between(*logged_previous_, logged);
    if (step.x_m > 0.0) {
      step.x_m = -step.x_m;
      step.y_m = -step.y_m;
      repaired = (repaired_previous_ * step).Normalized();
      offset_ = repaired * logged.Inverse();
      ++repaired_;
    }
  }
  logged_previous_ = logged;
  repaired_previous_ = repaired;
  velocities_ = 0;
  return repaired;
}

}  // namespace scanloc
