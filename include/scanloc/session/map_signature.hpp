#pragma once
// A map's own signature: how well the finished map explains the scans that built it. A session
// lays each scan on the map as it was then; scans laid later at the same places (a revisit a few
// centimetres off, a loop not closed) thicken the walls, and the finished map fits those same
// scans more loosely than it did. A localiser that judges the finished map's fit by rule 2 with the
// laser's prior E_max then rejects the right posture as often as it keeps it. So the session
// keeps a sample of the scans it laid, and at its end refines each from its posture on the
// finished map and learns a laser signature from their tests (median EV + k · robust σ). The
// bound is written with the map (summary.json, "map_signature") and is `scanloc localise`'s rule-2
// prior on that map until its own signature has learned.

#include <cstddef>
#include <optional>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/likelihood/laser_signature.hpp"
#include "scanloc/session/localisation.hpp"

namespace scanloc {

struct MapView;

// Every scan laid on the map, thinned to at most `capacity` spread evenly over the session: each
// `stride`-th one is kept, and when the sample is full every other one goes and the stride
// doubles. The sample does not depend on anything but the order of the scans (a resumed session
// keeps the same one).
class LaidScanSample {
 public:
  struct Entry {
    std::size_t index;  // the record's
    LaserScan scan;
    Pose2D T_world_robot;  // as laid
  };
  explicit LaidScanSample(std::size_t capacity = 200);
  void Add(std::size_t index, const LaserScan& scan, const Pose2D& T_world_robot);
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::size_t capacity_;
  std::size_t stride_ = 1;
  std::size_t seen_ = 0;
  std::vector<Entry> entries_;
};

// One sampled scan as the finished map judged it: where its refinement put it, and its EV.
struct MapSignatureSample {
  double x_m = 0.0, y_m = 0.0;
  double expect_value_m = 0.0;
};

struct MapSignature {
  double max_expect_value_m = 0.0;  // the learned bound (never below the prior)
  double median_expect_value_m = 0.0;
  std::size_t scans = 0;  // the sampled scans whose refinement had valid pairs
  bool learned = false;   // enough scans to learn from (else the bound is the prior)
  double wall_s = 0.0;    // what measuring it took
  std::vector<MapSignatureSample> samples;  // the scans it learned from, in the session's order
};

// Refines each sampled scan from its posture (`corrected[index]` when loop closure moved it) on
// the finished map and learns the signature of their Likelihood Tests, whatever the rules said.
MapSignature MeasureMapSignature(const MapView& map, const LaidScanSample& sample,
                                 const std::vector<std::optional<Pose2D>>& corrected,
                                 const LaserMounting& mounting, const LocalisationOptions& options,
                                 const LaserSignatureOptions& signature);

}  // namespace scanloc
