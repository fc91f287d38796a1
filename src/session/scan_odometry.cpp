#include "scanloc/session/scan_odometry.hpp"

#include <utility>

namespace scanloc {

std::optional<Pose2D> ScanOdometry::Next(const LaserScan& scan) {
  std::optional<Pose2D> pose;
  if (!previous_) {
    pose = pose_;  // the origin, or where the odometry was when reset
  } else if (previous_->live_size() > 0) {
    const MapView view{nullptr, &*previous_};
    const LocalisationResult result = Localise(view, scan, {{Pose2D(), "still"}}, mounting_,
                                               localisation_, RefinePolicy::kBestValid, 1);
    const RankedCandidate* kept = result.Kept();
    // Along a corridor's axis the scans do not tell the motion: none rather than standing still.
    if (kept != nullptr && result.validated() && kept->refinement &&
        !kept->refinement->degenerate) {
      pose_ = pose_ * kept->T_world_robot;
      pose = pose_;
      ++matched_;
    } else {
      ++failed_;
    }
  } else {
    ++failed_;
  }
  PointMap map(map_options_);
  map.InsertScan(scan, mounting_.LaserPose(Pose2D()));
  previous_.emplace(std::move(map));
  return pose;
}

}  // namespace scanloc
