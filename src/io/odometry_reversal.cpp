#include "scanloc/io/odometry_reversal.hpp"

#include <algorithm>
#include <cmath>

namespace scanloc {

Pose2D OdometryReversalRepair::Chain::Corrected(const Pose2D& logged) const {
  return offset ? (*offset * logged).Normalized() : logged;
}

Pose2D OdometryReversalRepair::Chain::Follow(const Pose2D& logged, bool reversing,
                                             std::size_t& repaired_count) {
  Pose2D repaired = Corrected(logged);
  if (logged_previous && reversing) {
    Pose2D step = Between(*logged_previous, logged);
    if (step.x_m > 0.0) {
      step.x_m = -step.x_m;
      step.y_m = -step.y_m;
      repaired = (repaired_previous * step).Normalized();
      offset = repaired * logged.Inverse();
      ++repaired_count;
    }
  }
  logged_previous = logged;
  repaired_previous = repaired;
  return repaired;
}

void OdometryReversalRepair::AddOdometry(const Pose2D& logged, double tv_mps, double timestamp_s) {
  odometry_.Follow(logged, tv_mps < -kReversingMps, repaired_);
  odometry_logged_ = logged;
  odometry_velocity_mps_ = tv_mps;
  odometry_timestamp_s_ = timestamp_s;
  NoteVelocity(tv_mps);
}

void OdometryReversalRepair::NoteVelocity(double tv_mps) {
  max_velocity_mps_ = velocities_ == 0 ? tv_mps : std::max(max_velocity_mps_, tv_mps);
  ++velocities_;
}

bool OdometryReversalRepair::InOdometryFrame(const Pose2D& logged, double timestamp_s) const {
  if (!odometry_logged_) return false;
  const Pose2D apart = Between(*odometry_logged_, logged);
  const double driven_m =
      std::abs(odometry_velocity_mps_) * std::abs(timestamp_s - odometry_timestamp_s_);
  return std::hypot(apart.x_m, apart.y_m) <= kSameFrameM + 2.0 * driven_m;
}

Pose2D OdometryReversalRepair::Repair(const Pose2D& logged, std::optional<double> velocity_mps,
                                      double timestamp_s) {
  if (velocity_mps) NoteVelocity(*velocity_mps);
  Pose2D repaired;
  if (InOdometryFrame(logged, timestamp_s)) {
    // The scans follow the ODOM chain's correction; their own chain is kept in step with it.
    repaired = odometry_.Corrected(logged);
    scans_.logged_previous = logged;
    scans_.repaired_previous = repaired;
    scans_.offset = odometry_.offset;
  } else {
    repaired =
        scans_.Follow(logged, velocities_ > 0 && max_velocity_mps_ < -kReversingMps, repaired_);
  }
  velocities_ = 0;
  return repaired;
}

}  // namespace scanloc
