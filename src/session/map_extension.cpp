#include "scanloc/session/map_extension.hpp"

namespace scanloc {

std::size_t ExtendMap(PointMap& map, const LaserScan& scan, const Pose2D& T_world_laser,
                      const MapExtensionOptions& options) {
  std::size_t carved = 0;
  if (options.free_space_margin_m > 0.0)
    carved = map.CarveFreeSpace(scan, T_world_laser, options.free_space_margin_m,
                                options.free_space_margin_per_m);
  map.InsertScan(scan, T_world_laser);  // (3.6)
  return carved;
}

}  // namespace scanloc
