#pragma once
// Odometry from the scans themselves, for a log that has none (a hand-held laser, pose fields left
// at zero): each scan is refined on a map of the scan before it alone, from where that one was
// (the robot moved little between them), and the match the rules validate is the increment. The
// poses it gives are a dead reckoning like a wheel odometry's: `scanloc localise` carries its
// hypotheses with them, so that a look-alike place that stands still while the scans move falls
// behind, where without any odometry every hypothesis could follow whatever motion fits it best.
// A scan the match does not validate gives no pose (the caller searches around its hypotheses,
// motion_search.hpp), and the next increment starts from it.
// The first scan's pose is the origin; after Reset, the next scan keeps the pose of the last one.

#include <optional>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/localisation.hpp"

namespace scanloc {

class ScanOdometry {
 public:
  ScanOdometry(const PointMapOptions& map_options, const LocalisationOptions& localisation,
               const LaserMounting& mounting)
      : map_options_(map_options), localisation_(localisation), mounting_(mounting) {}

  // The robot's odometry pose at `scan` (the first scan's is the origin), or nothing when the
  // match on the scan before is not validated (or there is no valid range).
  std::optional<Pose2D> Next(const LaserScan& scan);

  // Forgets the scan before (its successor is not the next scan given): the next scan keeps the
  // pose, and the increments go on from it.
  void Reset() { previous_.reset(); }

  std::size_t matched() const { return matched_; }
  std::size_t failed() const { return failed_; }

 private:
  PointMapOptions map_options_;
  LocalisationOptions localisation_;
  LaserMounting mounting_;
  std::optional<PointMap> previous_;  // the scan before, laid at the robot's origin
  Pose2D pose_;
  std::size_t matched_ = 0, failed_ = 0;
};

}  // namespace scanloc
