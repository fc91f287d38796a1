#pragma once
// Drives an environment's robot path and scans its world at every posture: the iterations of a
// simulated session, with their ground truth.

#include <cstddef>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/worlds/environments.hpp"

namespace scanloc {

struct SimulatedIteration {
  double timestamp_s = 0.0;
  LaserScan scan;
  Pose2D T_odom_robot;   // the drifting odometry
  Pose2D T_world_robot;  // the ground truth the scan was taken from
};

// All the randomness (odometry, range noise, missing returns) comes from `seed`, so a seed gives
// the same iterations on every run. Postures are rounded to 0.1 mm and 1 µrad before the scan is
// taken, ranges to 1 mm, so that stored files are small and hold exactly what was simulated.
// `max_iterations` > 0 stops the path early.
std::vector<SimulatedIteration> SimulateEnvironment(const Environment& environment, unsigned seed,
                                                    std::size_t max_iterations = 0);

}  // namespace scanloc
