#pragma once
// The odometry's own error, learned from the confirmed scans. Each confirmed scan's refinement
// moved its posture away from the odometry's prediction by a correction: the odometry's error over
// the step plus the matcher's. A refinement that moves the posture many times further than the
// recent confirmed scans' corrections did is more likely a wrong fit (a wall taken for its
// neighbour, a scan turned onto a corridor's other side) than the odometry slipping: given
// perfect odometry, a sparse log's session confirmed a scan turned 0.14 rad off (the recent
// median 0.004 rad) and lost its map. Such a refinement is neither confirmed nor kept: the scan
// keeps the prediction (never-lost issue: never worse than the odometry the data cannot
// disprove). The bound follows from the data, so it is tight for good odometry and loose for bad.
// A large correction stands when the scan supports it: on as much overlap as usual, along a
// direction the scan constrains as well as any other (a turn where the odometry slipped); it is
// refused on little overlap (a fit to the few walls in view) or, in position, along the direction
// the scan constrains least (a slide along a corridor's axis), or by a refinement still moving when
// its iterations ran out (a slide the covariance, taken where it stopped, does not show).

#include <cstddef>
#include <optional>

#include <Eigen/Core>

#include "scanloc/common/sorted_window.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct CorrectionGateOptions {
  // A refinement is refused when its correction exceeds factor · the median correction of the
  // remembered confirmed scans, in position or in heading, times √(n + 1) after n unconfirmed
  // scans in a row (the odometry's error grows like a random walk). 0 turns the gate off.
  double factor = 8.0;
  // Confirmed scans remembered (the most recent), and needed before the gate closes.
  int window = 500;
  int min_samples = 10;
  // A refused posture is confirmed after all when the next localised scan's refinement lands
  // within agree_factor · the median corrections of it (carried by the odometry): two scans that
  // agree on where the odometry went wrong are the odometry slipping, not a wrong fit.
  double agree_factor = 3.0;
  // A correction beyond the bound is refused when the refinement's match ratio (rule 1) is below
  // this fraction of the remembered confirmed scans' median ...
  double overlap_fraction = 0.75;
  // ... or when it exceeds the bound in position only (not in heading), along a direction whose
  // standard deviation (the refinement's covariance) is at least this many times the
  // best-constrained direction's, or by a refinement that did not converge.
  double weak_axis_ratio = 3.0;
  // Within a stretch of unconfirmed scans (after the first), a correction beyond the bound by a
  // refinement the rules did not validate is refused whatever its support: the exemptions above
  // (a turn where the odometry slipped, a converged fit along well-constrained directions, a
  // refused posture the next scan agrees with) need a scan the rules accept, or the first scan
  // the rules reject after confirmed ones, where a slip of the odometry is what failed it. ACES
  // seen over 120° turned 55° and moved 6.4 m on a scan rule 2 rejected, 150 unconfirmed scans
  // into a cluttered stretch; Fr079 kept a scan a metre slipped 13° at scan 113, the first its
  // rules rejected, and the refinement found the slip (docs/BENCHMARKS.md, "Unvalidated
  // corrections, and a batch its own lesson bent away").
  bool refuse_unvalidated = true;
  // ... and judged against the bound of one step, not the bound widened by the stretch's length:
  // the widening lets the session follow an odometry whose error grew over the stretch once a
  // scan confirms where it went, and a refinement the rules rejected confirms nothing. Off by
  // default: it saved ACES with a laser 1 cm noisier (seed 3, odometry calibrated) and lost Intel
  // seen over 120° (0.021 -> 0.54 m mean), whose unconfirmed refinements there followed the
  // odometry's growing error (docs/BENCHMARKS.md, "A miscalibrated odometry").
  bool unvalidated_one_step = false;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// The largest correction from the prediction a refinement may make: position (m), heading (rad).
struct CorrectionBound {
  double translation_m = 0.0;
  double rotation_rad = 0.0;
  bool Exceeded(const Pose2D& correction) const;
  bool ExceededInPosition(const Pose2D& correction) const;
  bool ExceededInHeading(const Pose2D& correction) const;
};

// What a refinement's scan says for it: its match ratio, the covariance of its position (world
// frame, m²) when the refinement has one, and whether it converged (false: it stopped at its
// iteration cap still moving; acapulco with a laser 1 cm noisier slid 0.59 m along a corridor
// over 15 outer iterations, its covariance stating 1 cm, and orebro's scan 107, given perfect
// odometry, 0.33 m).
struct RefinementSupport {
  double match_ratio = 0.0;
  std::optional<Eigen::Matrix2d> position_covariance;
  bool converged = true;
  bool validated = true;  // the rules validated the refinement
};

// The standard deviation of `covariance` along `direction` over its smallest one (1 when the
// direction is the best constrained; 0 when either is zero).
double WeakAxisRatio(const Eigen::Matrix2d& covariance, const Eigen::Vector2d& direction);

class CorrectionGate {
 public:
  explicit CorrectionGate(CorrectionGateOptions options = {}) : options_(options) {}

  // Learns the correction (Between(prediction, posture)) of a confirmed scan.
  void Add(const Pose2D& correction, double match_ratio);
  // The bound after `unconfirmed` scans in a row were not confirmed; none while the gate is off
  // or has seen fewer than min_samples confirmed scans.
  std::optional<CorrectionBound> Bound(int unconfirmed) const;
  std::size_t samples() const { return translations_m_.size(); }
  // A match ratio below overlap_fraction times the remembered confirmed scans' median (false
  // before min_samples).
  bool LowOverlap(double match_ratio) const;

  // Whether the refinement `refined` of a scan predicted at `prediction` goes beyond the bound
  // after `unconfirmed` scans in a row, unless it agrees with the posture refused at the previous
  // localised scan; it becomes the refused posture when it does (none when it does not).
  bool Refuses(const Pose2D& prediction, const Pose2D& refined, const RefinementSupport& support,
               int unconfirmed);
  // Whether the refinement `refined` is a slide still under way: it stopped at its iteration cap
  // (not converged), moving away from `prediction` along a direction weak_axis_ratio times less
  // constrained than the best. Whatever its size: for the scans before the slide check learns.
  bool Slides(const Pose2D& prediction, const Pose2D& refined,
              const RefinementSupport& support) const;
  // The refused posture follows the odometry.
  void Moved(const Pose2D& odometry_increment);
  // Resuming: the posture the recorded scan refused (none when it refused nothing).
  void Restore(const std::optional<Pose2D>& refused) { refused_ = refused; }

 private:
  CorrectionGateOptions options_;
  SortedWindow translations_m_, rotations_rad_, match_ratios_;
  std::optional<Pose2D> refused_;

  // Whether the refinement moved the position along a direction weak_axis_ratio times less
  // constrained (its covariance) than the best; false without a covariance.
  bool AlongWeakAxis(const Pose2D& prediction, const Pose2D& refined,
                     const RefinementSupport& support) const;
  // Whether the scan fails to support a correction beyond `bound` (see the options).
  bool Unsupported(const CorrectionBound& bound, const Pose2D& prediction, const Pose2D& refined,
                   const RefinementSupport& support, int unconfirmed) const;
  // Whether the refinement is one the rules rejected within a stretch they reject (see
  // refuse_unvalidated).
  bool Unvalidated(const RefinementSupport& support, int unconfirmed) const;
};

}  // namespace scanloc
