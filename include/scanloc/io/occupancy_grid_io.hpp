#pragma once
// Occupancy grids on disk in ROS map_server's format (map.pgm + map.yaml, as map_saver writes
// them), and grids built from a recorded log at a session's postures.

#include <string>
#include <vector>

#include "scanloc/io/trajectory.hpp"
#include "scanloc/maps/occupancy_grid.hpp"
#include "scanloc/maps/point_map.hpp"

namespace scanloc {

// map_saver's trinary pixels: what map_server reads back as occupied, free and unknown.
constexpr unsigned char kPgmOccupied = 0;
constexpr unsigned char kPgmFree = 254;
constexpr unsigned char kPgmUnknown = 205;

struct OccupancyGridFiles {
  std::string image_path;  // <dir>/<name>.pgm
  std::string yaml_path;   // <dir>/<name>.yaml
};

// The two files' paths, <dir>/<name>.pgm and <dir>/<name>.yaml.
OccupancyGridFiles OccupancyGridPaths(const std::string& dir, const std::string& name = "map");

// Writes <dir>/<name>.pgm (binary P5, row 0 at the top, i.e. the highest y) and <dir>/<name>.yaml
// (image, resolution, origin [x, y, 0] of the lower-left pixel, negate 0, occupied_thresh,
// free_thresh), each atomically. Throws std::runtime_error when they cannot be written.
OccupancyGridFiles WriteOccupancyGrid(const std::string& dir, const OccupancyGrid& grid,
                                      const std::string& name = "map");

// A grid as written: map_saver's trinary pixels, row 0 the image's top (the highest y).
struct OccupancyGridImage {
  double resolution_m = 0.05;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // world position of the lower-left corner
  std::size_t width = 0, height = 0;
  std::vector<unsigned char> pixels;  // width × height, kPgmOccupied / kPgmFree / kPgmUnknown
};

// Reads a map.yaml as WriteOccupancyGrid writes it (image, resolution, origin) and its binary PGM.
// Throws std::runtime_error naming the file and what was expected.
OccupancyGridImage ReadOccupancyGridImage(const std::string& yaml_path);

struct GridFromLogResult {
  OccupancyGrid grid;
  std::size_t scans_read = 0;  // scans in the log
  std::size_t scans_used = 0;  // scans with a posture of the same timestamp
};

// Reads the log (any format OpenIterationSource reads) and casts each scan whose timestamp has a
// posture in `T_world_robot` (within 0.1 ms: TUM files keep microseconds) from
// mounting.LaserPose(posture).
GridFromLogResult BuildGridFromLog(const std::string& log_path,
                                   const std::vector<StampedPose>& T_world_robot,
                                   const LaserMounting& mounting,
                                   const OccupancyGridOptions& options = {});

// Without the log: scans simulated from the point map (3.7, with occlusion) at each posture, in
// `layout`, cast as above. Walls the session never inserted stay unknown.
GridFromLogResult BuildGridFromPointMap(const PointMap& map,
                                        const std::vector<StampedPose>& T_world_robot,
                                        const LaserMounting& mounting, const ScanLayout& layout,
                                        const OccupancyGridOptions& options = {});

}  // namespace scanloc
