#pragma once
// Scans without odometry: a log that has none (a hand-held laser, a bag without an odometry
// topic), one whose odometry never moved while its scans did (pose fields left at zero), or
// session.ignore_odometry. Nothing predicts the motion since the last localised scan: the
// prediction is the last posture. When the rules confirm nothing from there, or the refinement had
// to move beyond the minima (a sparse log's scans lie 0.6–1 m apart), the map is searched around
// it (WideSearch) over a window as wide as the robot has lately moved between localised scans
// (the largest of the last `scans` confirmed motions, times `scale`), at least the minima. Before
// a few motions are known the window is the recovery's initial one. The odometry's own safeguards
// (the correction gate, an unconfirmed scan keeping its prediction) have nothing to stand on there
// and do not apply.

#include <cstddef>
#include <deque>
#include <optional>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/session/iteration.hpp"
#include "scanloc/session/localisation.hpp"
#include "scanloc/session/recovery.hpp"
#include "scanloc/session/wide_search.hpp"

namespace scanloc {

struct MotionSearchOptions {
  bool enabled = true;  // off: the scan is localised from the last posture alone, as before
  double scale = 1.5;
  int scans = 50;
  double min_half_width_m = 0.2;
  double min_half_yaw_rad = 0.1;
  // While the odometry has not moved since the first scan, a scan whose ranges differ from the
  // first scan's by more than this (the median over the beams valid in both) means the robot moved
  // without it (FrozenOdometry): a robot standing still sees the same ranges. 0: the odometry is
  // always believed. `scanloc localise` holding nothing without odometry searches the map again
  // only once the ranges moved this much since the last search (0: at every scan).
  double frozen_odometry_range_change_m = 0.1;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

class MotionWindow {
 public:
  // Motions learned before the window follows them.
  static constexpr std::size_t kMinMotions = 5;

  explicit MotionWindow(const MotionSearchOptions& options) : options_(options) {}

  // A confirmed motion from the previous localised scan to this one.
  void Add(const Pose2D& motion);
  // The window around `T_world_laser`: `initial` until kMinMotions are known, then `scale` times
  // the largest recent motion, within the minima and the maxima of `initial`'s recovery caps.
  SearchWindow Window(const Pose2D& T_world_laser, double initial_half_width_m,
                      double initial_half_yaw_rad, double max_half_width_m,
                      double max_half_yaw_rad) const;
  // The same, `recovery`'s initial window and caps.
  SearchWindow Window(const Pose2D& T_world_laser, const RecoveryOptions& recovery) const;
  std::size_t motions() const { return translations_m_.size(); }

 private:
  MotionSearchOptions options_;
  std::deque<double> translations_m_, rotations_rad_;
};

// Odometry that has not moved since the first scan while the scans did (a log whose pose fields
// were left at zero): once a scan's ranges differ from the first scan's by more than
// `range_change_m` (the median over the beams; 0: never), the odometry is set aside until it
// moves itself. A robot standing still sees the same ranges, and its resting odometry is believed.
class FrozenOdometry {
 public:
  explicit FrozenOdometry(double range_change_m) : range_change_m_(range_change_m) {}

  // Whether the odometry `given` carries is to be set aside for it.
  bool SetAside(const Iteration& given);

 private:
  double range_change_m_;
  std::optional<Pose2D> first_;
  std::optional<LaserScan> first_scan_;
  bool moved_ = false;         // since the first scan's
  bool found_frozen_ = false;  // not moved while the ranges did
};

// Whether a scan is localised without odometry and searched for over the motion seen lately:
// none to predict it with, not the first scan, and the motion search on.
bool SearchesMotion(const Iteration& iteration, std::size_t scans_before,
                    const MotionSearchOptions& options);

// Whether a scan localised from the last posture `from` (no odometry to predict with) is searched
// for: the rules confirmed nothing there, or the kept refinement had to move beyond the minima.
bool NeedsMotionSearch(const LocalisationResult& result, const Pose2D& from,
                       const MotionSearchOptions& options);

// `given`, or a copy of it in `stripped` without its odometry when `strip`.
const Iteration& WithoutOdometryIf(bool strip, const Iteration& given,
                                   std::optional<Iteration>& stripped);

// The median of |a_k − b_k| over the beams valid in both scans, m; nothing when the scans' layouts
// differ or fewer than `min_beams` beams are valid in both.
std::optional<double> MedianRangeChange(const LaserScan& a, const LaserScan& b,
                                        std::size_t min_beams = 10);

}  // namespace scanloc
