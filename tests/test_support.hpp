#pragma once
// Helpers shared by the tests: synthetic rooms, layouts, the public datasets' location.

#include <gtest/gtest.h>

#include <string>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc::testing {

// An axis-aligned rectangular room [0, width] × [0, height] as four segments.
LineMap RectangleRoom(double width_m, double height_m);

// The chapter's classroom: a 6.3 m × 7 m room with an L-shaped board in the north-east corner.
LineMap Classroom();

// An 8 m × 6 m room with an L-shaped feature near one corner (the classroom's asymmetry).
LineMap SmallRoomWithL();

// The map seen from T_world_laser with `beams` beams over 360°, with Gaussian range noise of
// sigma_m drawn from `seed` (none when sigma_m is 0).
LaserScan NoisyScan(const LineMap& map, const Pose2D& T_world_laser, std::size_t beams,
                    double sigma_m, unsigned seed);

// A LaserScan whose ranges are the given simulated scan's (no-return beams become -1.0).
LaserScan ScanFromSimulation(const SimulatedScan& simulated);

// The folder of the public benchmark logs (SCANLOC_DATASETS, else ../shared/datasets), or "" when
// it does not exist.
std::string DatasetsDir();

// A fresh temporary directory for one test.
std::string TemporaryDir();

// A test with its own temporary directory, removed afterwards.
class TemporaryDirTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = TemporaryDir(); }
  void TearDown() override;
  // Writes `content` to a file of the directory and returns its path.
  std::string Write(const std::string& name, const std::string& content) const;
  std::string dir_;
};

}  // namespace scanloc::testing
