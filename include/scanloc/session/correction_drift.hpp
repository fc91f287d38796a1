#pragma once
// The session's corrections of the odometry, summed over the last stretch of path. The odometry's
// errors partly cancel from scan to scan, and a miscalibrated odometry errs by a steady share of
// each step, so that the sums stay alike along a log. A matcher sliding along a corridor that a
// short-range laser sees no end of corrects the same way at every scan, on a map it lays itself,
// each step within the correction gate's bound: ACES seen up to 5.6 m summed 4.6 m of corrections
// over 5 m of path, 43 times the median sum of its session so far. The bound is learned as the
// correction gate's is: a confirmed correction that takes the sum beyond factor · the median of
// the sums the recent confirmed scans left, and farther than it was, is refused as the gate
// refuses one, where the scan does not demand it (the session's JudgeCorrection: the prediction
// passes the rules as given and the map does not disprove it), and the scan is confirmed at the
// prediction. The bound is tight for good odometry and loose for bad
// (docs/BENCHMARKS.md, "Corrections that add up to a slide"), and never below the correction
// gate's bound on one correction. A refused scan is held: the window does not move on over the
// path driven while held, so that a slide cannot go on as the old corrections leave the window,
// and the bound widens with that path as the odometry's error grows, like a random walk
// (× √(1 + held path / window)), so that an odometry that truly went wrong is followed in the end.

#include <cstddef>
#include <deque>
#include <optional>
#include <utility>

#include <Eigen/Core>

#include "scanloc/common/sorted_window.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct CorrectionDriftOptions {
  // The stretch of path the confirmed corrections are summed over, m; 0 turns the check off.
  double window_m = 5.0;
  // The largest sum a correction may take them to, as a multiple of the median sum the recent
  // confirmed scans left.
  double factor = 8.0;
  // Sums remembered (the most recent), and needed before the check closes.
  int samples = 500;
  int min_samples = 20;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// What the slide check said of one confirmed correction: the window's sum before it and with it,
// and the bound in force (m).
struct SlideCheck {
  double before_m = 0.0, after_m = 0.0, bound_m = 0.0;
  // The correction takes the sum beyond the bound, and farther than it was.
  bool Refused() const { return after_m > bound_m && after_m > before_m; }
};

class CorrectionDrift {
 public:
  explicit CorrectionDrift(CorrectionDriftOptions options = {});

  // A localised scan's prediction: the path driven since the last posture kept.
  void Predicted(const Pose2D& prediction);
  // The check of a confirmed correction (the kept posture's position less the prediction's, world
  // frame) against the bound, at least floor_m; none while the check is open.
  std::optional<SlideCheck> Check(const Eigen::Vector2d& correction, double floor_m = 0.0) const;
  bool Refuses(const Eigen::Vector2d& correction, double floor_m = 0.0) const {
    const std::optional<SlideCheck> check = Check(correction, floor_m);
    return check && check->Refused();
  }
  // The posture the scan kept, and its correction when it was confirmed (its sum is learned);
  // `held` when its correction was refused.
  void Kept(const Pose2D& posture, const std::optional<Eigen::Vector2d>& correction, bool held);
  // The session goes on from `posture` instead of the one it kept (a closure's solve moved it):
  // the next step is driven from there, the jump is no path.
  void Moved(const Pose2D& posture);
  // A lost session found its posture again at `posture` (the wide search's, not a correction of
  // the odometry): the window starts afresh from there; the sums learned are kept.
  void Restart(const Pose2D& posture);
  // The magnitude of the window's sum, m.
  double Sum() const;
  // The largest sum a correction may leave, m; none while the check is off or has learned fewer
  // than min_samples sums.
  std::optional<double> Bound() const;

 private:
  CorrectionDriftOptions options_;
  double path_m_ = 0.0;  // driven while not held
  double step_m_ = 0.0;  // from the last posture kept to the prediction
  double held_m_ = 0.0;  // driven while held since the sum was last within the learned bound
  std::optional<Pose2D> last_;
  std::deque<std::pair<double, Eigen::Vector2d>> window_;  // (path at the scan, its correction)
  SortedWindow sums_m_;
  // The corrections summed over the window, as it will stand with the step driven (oldest first).
  Eigen::Vector2d Total() const;
};

}  // namespace scanloc
