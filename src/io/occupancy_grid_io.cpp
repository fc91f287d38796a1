#include "scanloc/io/occupancy_grid_io.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <ostream>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {
namespace {

// TUM trajectories keep microseconds; a scan's posture is the one within this of its stamp.
constexpr double kStampToleranceS = 1e-4;

unsigned char Pixel(CellState state) {
  switch (state) {
    case CellState::kOccupied:
      return kPgmOccupied;
    case CellState::kFree:
      return kPgmFree;
    case CellState::kUnknown:
      break;
  }
  return kPgmUnknown;
}

}  // namespace

OccupancyGridFiles WriteOccupancyGrid(const std::string& dir, const OccupancyGrid& grid,
                                      const std::string& name) {
  OccupancyGridFiles files{dir + "/" + name + ".pgm", dir + "/" + name + ".yaml"};
  WriteFileAtomically(files.image_path, [&](std::ostream& out) {
    out << "P5\n# scanloc occupancy grid, " << grid.resolution_m << " m/pixel\n"
        << grid.width << ' ' << grid.height << "\n255\n";
    std::string row(grid.width, '\0');
    for (std::size_t r = 0; r < grid.height; ++r) {
      const std::size_t y = grid.height - 1 - r;  // image rows run from the top
      for (std::size_t x = 0; x < grid.width; ++x)
        row[x] = static_cast<char>(Pixel(grid.State(x, y)));
      out.write(row.data(), static_cast<std::streamsize>(row.size()));
    }
  });
  WriteFileAtomically(files.yaml_path, [&](std::ostream& out) {
    out << std::setprecision(10) << "image: " << name << ".pgm\n"
        << "resolution: " << grid.resolution_m << "\n"
        << "origin: [" << grid.origin_m.x() << ", " << grid.origin_m.y() << ", 0.0]\n"
        << "negate: 0\n"
        << "occupied_thresh: " << grid.occupied_probability << "\n"
        << "free_thresh: " << grid.free_probability << "\n";
  });
  return files;
}

GridFromLogResult BuildGridFromLog(const std::string& log_path,
                                   const std::vector<StampedPose>& T_world_robot,
                                   const LaserMounting& mounting,
                                   const OccupancyGridOptions& options) {
  std::vector<StampedPose> poses = T_world_robot;
  std::stable_sort(poses.begin(), poses.end(), [](const StampedPose& a, const StampedPose& b) {
    return a.timestamp_s < b.timestamp_s;
  });
  OccupancyGridBuilder builder(options);
  GridFromLogResult result;
  auto source = OpenIterationSource(log_path);
  Iteration iteration;
  while (source->Next(iteration)) {
    ++result.scans_read;
    const double t = iteration.timestamp_s;
    auto it =
        std::lower_bound(poses.begin(), poses.end(), t - kStampToleranceS,
                         [](const StampedPose& p, double stamp) { return p.timestamp_s < stamp; });
    if (it == poses.end() || std::abs(it->timestamp_s - t) > kStampToleranceS) continue;
    builder.AddScan(iteration.scan, mounting.LaserPose(it->pose));
    ++result.scans_used;
  }
  result.grid = builder.Build();
  return result;
}

GridFromLogResult BuildGridFromPointMap(const PointMap& map,
                                        const std::vector<StampedPose>& T_world_robot,
                                        const LaserMounting& mounting, const ScanLayout& layout,
                                        const OccupancyGridOptions& options) {
  OccupancyGridBuilder builder(options);
  GridFromLogResult result;
  for (const StampedPose& pose : T_world_robot) {
    const Pose2D T_world_laser = mounting.LaserPose(pose.pose);
    const SimulatedScan simulated = SimulateFromPoints(map, layout, T_world_laser);
    LaserScan scan;
    scan.layout = simulated.layout;
    scan.ranges_m = simulated.ranges_m;
    scan.timestamp_s = pose.timestamp_s;
    builder.AddScan(scan, T_world_laser);
    ++result.scans_read;
    ++result.scans_used;
  }
  result.grid = builder.Build();
  return result;
}

}  // namespace scanloc
