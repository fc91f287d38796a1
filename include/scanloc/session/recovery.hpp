#pragma once
// Knowing when the session is lost, and how wide to search when it is. The odometry's uncertainty
// grows with the distance driven and the angle turned since the last confirmed scan; after a few
// unconfirmed scans in a row the session counts itself lost and adds the wide search's candidates,
// over a window that grows with that uncertainty, to its own (never-lost issue; Olson 2009).

#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/session/wide_search.hpp"

namespace scanloc {

struct RecoveryOptions {
  // Localised scans in a row that the rules did not confirm before the session counts itself lost
  // and searches wide. 0 turns the wide search off (the default until it keeps the benchmark logs
  // as good as without it: docs/BENCHMARKS.md).
  int lost_after_unconfirmed = 0;
  // The window's half width: min_half_width_m + translation_error_per_m · metres driven since the
  // last confirmed scan, at most max_half_width_m.
  double min_half_width_m = 1.0;
  double translation_error_per_m = 0.1;
  double max_half_width_m = 3.0;
  // (The caps bound the search's cost per scan: a session lost for long searches no wider.)
  // Its half heading range: min_half_yaw_rad + heading_error_per_rad · radians turned +
  // heading_error_per_m · metres driven, at most max_half_yaw_rad.
  double min_half_yaw_rad = 0.45;
  double heading_error_per_rad = 0.1;
  double heading_error_per_m = 0.02;
  double max_half_yaw_rad = 0.8;
  WideSearchOptions search;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// The odometry driven since the last confirmed scan, and the unconfirmed scans since.
class DriftTracker {
 public:
  explicit DriftTracker(const RecoveryOptions& options) : options_(options) {}

  void Moved(const Pose2D& odometry_increment);
  // A localised scan: confirmed resets the drift; unconfirmed counts towards being lost.
  void Localised(bool confirmed);

  bool lost() const {
    return options_.lost_after_unconfirmed > 0 && unconfirmed_ >= options_.lost_after_unconfirmed;
  }
  int unconfirmed() const { return unconfirmed_; }
  double distance_m() const { return distance_m_; }
  double turn_rad() const { return turn_rad_; }
  // The window around the predicted laser posture that the odometry's drift may have left.
  SearchWindow Window(const Pose2D& T_world_laser_predicted) const;

 private:
  RecoveryOptions options_;
  int unconfirmed_ = 0;
  double distance_m_ = 0.0, turn_rad_ = 0.0;
};

}  // namespace scanloc
