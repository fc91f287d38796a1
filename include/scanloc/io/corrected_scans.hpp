#pragma once
// The scans of a benchmark log that have a corrected (ground-truth) pose: the reference for
// accuracy measured against the world.

#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/io/carmen_log.hpp"

namespace scanloc {

struct CorrectedScan {
  LaserScan scan;
  Pose2D T_world_laser;  // the corrected robot pose with the log's laser mounting
};

// Reads `log` in file order and keeps the laser scans whose timestamp has a pose in
// `corrected_poses` (`timestamp x y theta` per line) within 10 µs.
std::vector<CorrectedScan> ReadCorrectedScans(const std::string& log,
                                              const std::string& corrected_poses,
                                              CarmenOptions options = {});

}  // namespace scanloc
