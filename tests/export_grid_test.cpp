// `scanloc session` on the shipped classroom bag, then `scanloc export-grid`: the grid read back by
// ROS map_server's rules against the session's point map.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "run_scanloc.hpp"
#include "scanloc/io/ros_bag_source.hpp"
#include "scanloc/maps/point_map_io.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

// A map as map_server (ROS 1, image_loader.cpp) reads it: 100 occupied, 0 free, -1 unknown.
struct MapServerMap {
  std::map<std::string, std::string> yaml;
  std::size_t width = 0, height = 0;
  double resolution_m = 0.0, origin_x_m = 0.0, origin_y_m = 0.0;
  std::vector<int> cells;  // row-major, row 0 at the lowest y (the image's bottom row)
  int At(long x, long y) const {
    if (x < 0 || y < 0 || x >= static_cast<long>(width) || y >= static_cast<long>(height))
      return -1;
    return cells[static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x)];
  }
  // Occupied within `radius` cells of the cell holding the point.
  bool OccupiedNear(double x_m, double y_m, long radius) const {
    const long cx = static_cast<long>(std::floor((x_m - origin_x_m) / resolution_m));
    const long cy = static_cast<long>(std::floor((y_m - origin_y_m) / resolution_m));
    for (long dx = -radius; dx <= radius; ++dx)
      for (long dy = -radius; dy <= radius; ++dy)
        if (At(cx + dx, cy + dy) == 100) return true;
    return false;
  }
};

// The next header token of a PGM, skipping `#` comments.
std::string PgmToken(std::istream& in) {
  std::string token;
  while (in >> token && token.front() == '#') std::getline(in, token);
  return token;
}

MapServerMap ReadAsMapServer(const std::string& yaml_path, const std::string& dir) {
  MapServerMap m;
  std::ifstream yaml(yaml_path);
  for (std::string line; std::getline(yaml, line);) {
    const auto colon = line.find(':');
    if (colon != std::string::npos)
      m.yaml[line.substr(0, colon)] = line.substr(line.find_first_not_of(' ', colon + 1));
  }
  m.resolution_m = std::stod(m.yaml["resolution"]);
  std::sscanf(m.yaml["origin"].c_str(), "[%lf, %lf", &m.origin_x_m, &m.origin_y_m);
  const bool negate = m.yaml["negate"] != "0";
  const double occupied_thresh = std::stod(m.yaml["occupied_thresh"]);
  const double free_thresh = std::stod(m.yaml["free_thresh"]);
  std::ifstream pgm(dir + "/" + m.yaml["image"], std::ios::binary);
  EXPECT_EQ(PgmToken(pgm), "P5");
  m.width = std::stoul(PgmToken(pgm));
  m.height = std::stoul(PgmToken(pgm));
  EXPECT_EQ(PgmToken(pgm), "255");
  pgm.get();  // the single whitespace before the pixels
  std::string pixels(m.width * m.height, '\0');
  pgm.read(pixels.data(), static_cast<std::streamsize>(pixels.size()));
  EXPECT_EQ(static_cast<std::size_t>(pgm.gcount()), pixels.size());
  m.cells.assign(pixels.size(), -1);
  for (std::size_t j = 0; j < m.height; ++j)
    for (std::size_t i = 0; i < m.width; ++i) {
      double value = static_cast<unsigned char>(pixels[j * m.width + i]);
      if (!negate) value = 255.0 - value;
      const double occupancy = value / 255.0;
      const int cell = occupancy > occupied_thresh ? 100 : occupancy < free_thresh ? 0 : -1;
      m.cells[(m.height - 1 - j) * m.width + i] = cell;  // image rows run from the top
    }
  return m;
}

class ExportGridTest : public testing::TemporaryDirTest {
 protected:
  // A session on the first 20 scans of the classroom bag, in dir_/run.
  std::string RunSession() {
    const std::string source = SCANLOC_SOURCE_DIR;
    const std::string run = dir_ + "/run";
    const auto session = testing::RunScanloc(
        {"session", "--log", source + "/datasets/classroom/classroom.bag", "--line-map",
         source + "/datasets/classroom/classroom.lines", "--initial-pose", "1.126", "3.112",
         "0.0463", "--max-scans", "20", "--out", run, "--quiet"},
        dir_);
    EXPECT_TRUE(session.exited && session.exit_code == 0) << session;
    return run;
  }
};

TEST_F(ExportGridTest, GridOfAClassroomSessionReadsByMapServerRulesWithWallsOnMapPoints) {
  if (!RosBagSupported()) GTEST_SKIP() << "built without ROS bag support";
  const std::string run = RunSession();
  // The session's own grid (what export-grid builds too: see the next test).
  const MapServerMap m = ReadAsMapServer(run + "/map.yaml", run);
  EXPECT_EQ(m.yaml.at("image"), "map.pgm");
  EXPECT_EQ(m.yaml.at("negate"), "0");
  EXPECT_DOUBLE_EQ(m.resolution_m, 0.05);
  EXPECT_DOUBLE_EQ(std::stod(m.yaml.at("occupied_thresh")), 0.65);
  EXPECT_DOUBLE_EQ(std::stod(m.yaml.at("free_thresh")), 0.196);

  const PointMap points = LoadPointMapPcd(run + "/map.pcd");
  ASSERT_GT(points.live_size(), 500u);  // 634 with the defaults
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e9), high = -low;
  std::size_t on_walls = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points.alive(i)) continue;
    low = low.cwiseMin(points.point(i));
    high = high.cwiseMax(points.point(i));
    on_walls += m.OccupiedNear(points.point(i).x(), points.point(i).y(), 1);
  }
  // The grid covers the map's extent plus the two-cell margin (and not much more: the laser's
  // positions lie inside the room).
  const double r = m.resolution_m;
  EXPECT_LE(m.origin_x_m, low.x() - 2 * r + 1e-9);
  EXPECT_GE(m.origin_x_m, low.x() - 4 * r);
  EXPECT_LE(m.origin_y_m, low.y() - 2 * r + 1e-9);
  EXPECT_GE(m.origin_y_m, low.y() - 4 * r);
  EXPECT_NEAR(m.origin_x_m + m.width * r, high.x() + 3 * r, 1.5 * r);
  EXPECT_NEAR(m.origin_y_m + m.height * r, high.y() + 3 * r, 1.5 * r);
  // Map points lie on occupied cells (or their neighbours), and occupied cells on map points. 0.92
  // and 0.97 at the time of writing: beams at grazing incidence cross wall cells seen from
  // elsewhere and clear some of them.
  const double fraction_on_walls = static_cast<double>(on_walls) / points.live_size();
  EXPECT_GE(fraction_on_walls, 0.9) << on_walls << " of " << points.live_size();
  std::size_t occupied = 0, occupied_on_points = 0, free_cells = 0;
  for (std::size_t y = 0; y < m.height; ++y)
    for (std::size_t x = 0; x < m.width; ++x) {
      free_cells += m.At(x, y) == 0;
      if (m.At(x, y) != 100) continue;
      ++occupied;
      const Eigen::Vector2d centre(m.origin_x_m + (x + 0.5) * r, m.origin_y_m + (y + 0.5) * r);
      occupied_on_points += !points.RadiusSearch(centre, 1.5 * r).empty();
    }
  EXPECT_GE(static_cast<double>(occupied_on_points) / occupied, 0.95)
      << occupied_on_points << " of " << occupied;
  EXPECT_GT(free_cells, 5 * occupied);  // the room's floor
  std::printf(
      "export-grid: %zu × %zu cells, %zu occupied (%zu on map points), %zu free; %.4f of "
      "%zu map points on occupied cells\n",
      m.width, m.height, occupied, occupied_on_points, free_cells, fraction_on_walls,
      points.live_size());
}

TEST_F(ExportGridTest, TheSessionsOwnGridIsTheOneExportGridBuildsFromItsRunFolder) {
  if (!RosBagSupported()) GTEST_SKIP() << "built without ROS bag support";
  const std::string run = RunSession();
  // export-grid does not replace the session's grid unless told to.
  const auto refused = testing::RunScanloc({"export-grid", run}, dir_);
  EXPECT_NE(refused.exit_code, 0) << refused;
  EXPECT_TRUE(testing::Contains(refused.err, run + "/map.pgm already exists; give --force"))
      << refused;
  const auto exported =
      testing::RunScanloc({"export-grid", run, "--out", dir_ + "/exported"}, dir_);
  ASSERT_TRUE(exported.exited && exported.exit_code == 0) << exported;
  const MapServerMap session = ReadAsMapServer(run + "/map.yaml", run);
  const MapServerMap rebuilt = ReadAsMapServer(dir_ + "/exported/map.yaml", dir_ + "/exported");
  EXPECT_EQ(session.yaml, rebuilt.yaml);
  ASSERT_EQ(session.cells.size(), rebuilt.cells.size());
  // export-grid takes the postures from trajectory.tum (micrometres, nanoradians): a beam may
  // end on the other side of a cell boundary now and then.
  std::size_t differ = 0;
  for (std::size_t i = 0; i < session.cells.size(); ++i)
    differ += session.cells[i] != rebuilt.cells[i];
  EXPECT_LE(differ, session.cells.size() / 1000) << differ << " of " << session.cells.size();
  const auto forced = testing::RunScanloc({"export-grid", run, "--force"}, dir_);
  EXPECT_EQ(forced.exit_code, 0) << forced;
  std::printf("the session's grid and export-grid's differ in %zu of %zu cells\n", differ,
              session.cells.size());
}

TEST_F(ExportGridTest, RunFolderWithoutItsLogFallsBackToScansSimulatedFromItsMap) {
  if (!RosBagSupported()) GTEST_SKIP() << "built without ROS bag support";
  const std::string run = RunSession();
  Write("run/summary.json", R"({"inputs": {"log": "/nonexistent/run.bag"},
      "config": {"mounting": {"x_m": 0.15, "y_m": 0.0, "yaw_rad": 0.0}}})");
  const auto grid = testing::RunScanloc({"export-grid", run, "--name", "from_map"}, dir_);
  ASSERT_TRUE(grid.exited && grid.exit_code == 0) << grid;
  EXPECT_NE(grid.out.find("simulated from map.pcd"), std::string::npos) << grid;
  const MapServerMap m = ReadAsMapServer(run + "/from_map.yaml", run);
  EXPECT_EQ(m.yaml.at("image"), "from_map.pgm");
  const PointMap points = LoadPointMapPcd(run + "/map.pcd");
  std::size_t on_walls = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    on_walls += points.alive(i) && m.OccupiedNear(points.point(i).x(), points.point(i).y(), 1);
  EXPECT_GE(static_cast<double>(on_walls) / points.live_size(), 0.9)
      << on_walls << " of " << points.live_size();
}

TEST_F(ExportGridTest, RunFolderWithoutItsLogOrMapIsAnErrorSayingSo) {
  Write("summary.json", R"({"inputs": {"log": "/nonexistent/run.bag"}})");
  Write("trajectory.tum", "");
  const auto r = testing::RunScanloc({"export-grid", dir_}, dir_);
  EXPECT_EQ(r.exit_code, 1) << r;
  EXPECT_NE(
      r.err.find("/nonexistent/run.bag is absent and there is no map.pcd; give the log with --log"),
      std::string::npos)
      << r;
}

}  // namespace
}  // namespace scanloc
