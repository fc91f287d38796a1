#include "scanloc/io/occupancy_grid_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <ostream>
#include <stdexcept>

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

// The next header token of a PGM, skipping `#` comments.
std::string PgmToken(std::istream& in) {
  std::string token;
  while (in >> token && token.front() == '#') std::getline(in, token);
  return token;
}

std::map<std::string, std::string> YamlKeys(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::map<std::string, std::string> keys;
  for (std::string line; std::getline(in, line);) {
    const auto colon = line.find(':');
    const auto value = line.find_first_not_of(' ', colon + 1);
    if (colon != std::string::npos && value != std::string::npos)
      keys[line.substr(0, colon)] = line.substr(value);
  }
  for (const char* key : {"image", "resolution", "origin"})
    if (!keys.count(key)) throw std::runtime_error(path + ": expected the key " + key);
  return keys;
}

void ReadPgmPixels(const std::string& path, OccupancyGridImage& image) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  const std::string magic = PgmToken(in), width = PgmToken(in), height = PgmToken(in),
                    depth = PgmToken(in);
  try {
    image.width = std::stoul(width);
    image.height = std::stoul(height);
  } catch (const std::exception&) {
    image.width = image.height = 0;
  }
  constexpr std::size_t kMaxCells = std::size_t{1} << 28;  // 16384² cells
  if (magic != "P5" || depth != "255" || image.width == 0 || image.height == 0 ||
      image.width > kMaxCells / image.height)
    throw std::runtime_error(path +
                             ": expected a binary PGM (P5, 255 levels) of at most 2^28 pixels");
  in.get();  // the single whitespace before the pixels
  image.pixels.resize(image.width * image.height);
  in.read(reinterpret_cast<char*>(image.pixels.data()),
          static_cast<std::streamsize>(image.pixels.size()));
  if (static_cast<std::size_t>(in.gcount()) != image.pixels.size())
    throw std::runtime_error(path + ": expected " + std::to_string(image.pixels.size()) +
                             " pixels, the file ends before");
}

}  // namespace

OccupancyGridImage ReadOccupancyGridImage(const std::string& yaml_path) {
  const auto keys = YamlKeys(yaml_path);
  OccupancyGridImage image;
  double x = 0.0, y = 0.0;
  try {
    image.resolution_m = std::stod(keys.at("resolution"));
  } catch (const std::exception&) {
    image.resolution_m = 0.0;
  }
  if (!(image.resolution_m > 0.0) || !std::isfinite(image.resolution_m) ||
      std::sscanf(keys.at("origin").c_str(), "[%lf, %lf", &x, &y) != 2 || !std::isfinite(x) ||
      !std::isfinite(y))
    throw std::runtime_error(yaml_path +
                             ": expected a positive resolution and origin: [x, y, yaw]");
  image.origin_m = {x, y};
  const std::filesystem::path dir = std::filesystem::path(yaml_path).parent_path();
  ReadPgmPixels((dir / keys.at("image")).string(), image);
  return image;
}

OccupancyGridFiles OccupancyGridPaths(const std::string& dir, const std::string& name) {
  return {dir + "/" + name + ".pgm", dir + "/" + name + ".yaml"};
}

OccupancyGridFiles WriteOccupancyGrid(const std::string& dir, const OccupancyGrid& grid,
                                      const std::string& name) {
  const OccupancyGridFiles files = OccupancyGridPaths(dir, name);
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
