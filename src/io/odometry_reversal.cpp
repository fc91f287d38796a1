#include "scanloc/io/odometry_reversal.hpp"

namespace scanloc {

Pose2D OdometryReversalRepair::Follow(const Pose2D& logged, std::optional<double> velocity_mps) {
  if (velocity_mps) velocity_mps_ = velocity_mps;
  Pose2D repaired = offset_ ? (*offset_ * logged).Normalized() : logged;
  if (logged_previous_ && velocity_mps_ && *velocity_mps_ < -kReversingMps) {
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
  return repaired;
}

}  // namespace scanloc
