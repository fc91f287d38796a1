#pragma once
// Extending the map with a localised scan: its beams first carve the free space they crossed
// (map points seen through are removed: people who moved, opened doors, the copy of a wall an
// earlier drifted pass laid in front of it), then its points are inserted (3.6). The session and
// the report's replay both extend the map through this, so both hold the same map.

#include <cstddef>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/maps/point_map.hpp"

namespace scanloc {

struct MapExtensionOptions {
  // A map point counts as seen through when it lies more than margin_m + margin_per_m · r in
  // front of the return r (the end points' uncertainty grows with the range: 0.5° of heading is
  // 9 cm at 10 m). margin_m = 0 disables carving.
  double free_space_margin_m = 0.1;
  double free_space_margin_per_m = 0.01;
  // A scan carves only what was laid before it, so a person laid by the last scans of a session
  // into a place that earlier scans saw free would stay in the saved map. When on, the map the
  // session saves is carved a second time, each node's scan against the points laid after it
  // (LoopCloser::Render); the online map, and so the trajectory, are not changed.
  bool carve_with_earlier_scans = true;
};

// Carves, then inserts the scan seen from T_world_laser; returns the number of points carved.
std::size_t ExtendMap(PointMap& map, const LaserScan& scan, const Pose2D& T_world_laser,
                      const MapExtensionOptions& options);

}  // namespace scanloc
