#pragma once
// Helpers shared by the tests: synthetic rooms, layouts, the public datasets' location.

#include <gtest/gtest.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/io/trajectory.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/simulation/simulated_scan.hpp"
#include "scanloc/worlds/laser_simulator.hpp"

namespace scanloc::testing {

// An axis-aligned rectangular room [0, width] × [0, height] as four segments.
LineMap RectangleRoom(double width_m, double height_m);

// The chapter's classroom: a 6.3 m × 7 m room with an L-shaped board in the north-east corner.
LineMap Classroom();

// An 8 m × 6 m room with an L-shaped feature near one corner (the classroom's asymmetry).
LineMap SmallRoomWithL();

// A 24 × 16 m building with a 16 × 8 m block in its middle: a 4 m wide ring corridor, with
// boxes and recesses along it so that no stretch is a featureless corridor.
LineMap RingBuilding();
// The laser driven around it: 181 beams over 180°, 12 m, 1 cm of range noise.
LaserSimulatorOptions RingBuildingLaser();

// The map seen from T_world_laser with `beams` beams over 360°, with Gaussian range noise of
// sigma_m drawn from `seed` (none when sigma_m is 0).
LaserScan NoisyScan(const LineMap& map, const Pose2D& T_world_laser, std::size_t beams,
                    double sigma_m, unsigned seed);

// A LaserScan whose ranges are the given simulated scan's (no-return beams become -1.0).
LaserScan ScanFromSimulation(const SimulatedScan& simulated);

// The folder of the public benchmark logs (SCANLOC_DATASETS, else ../shared/datasets), or "" when
// it does not exist.
std::string DatasetsDir();

// A copy of the public log `log` (its name in DatasetsDir(), without ".clf.gz") at `path`, gzip
// compressed, whose FLASER pose fields (x y θ and the odometry's) are all zero: a log whose
// odometry was never filled in. Fails the test when a file cannot be opened.
void WriteWithZeroedOdometry(const std::string& log, const std::string& path);

// A copy of the public log `log` at `path`, gzip compressed, that keeps a FLASER only after its
// odometry moved kSparseKeepM or turned kSparseKeepRad from the last one kept (a log kept as the
// Radish logs are, a scan every metre or so); every other line (ODOM, PARAM) is kept. Fails the
// test when a file cannot be opened.
void WriteSparse(const std::string& log, const std::string& path);

// A sparse log keeps a scan once the odometry moved this far or turned this much since the last
// scan kept (m, rad): SparseKeeps says whether a step from it does.
constexpr double kSparseKeepM = 0.8, kSparseKeepRad = 0.3;
bool SparseKeeps(const Pose2D& odometry_step);

// Why a test that needs the public logs was skipped.
inline constexpr char kNoDatasets[] =
    "public logs not found: set SCANLOC_DATASETS (default ../shared/datasets)";

// In a test body: `dir` holds the public logs' folder, or the test is skipped saying why.
#define SCANLOC_REQUIRE_DATASETS(dir)                        \
  const std::string dir = ::scanloc::testing::DatasetsDir(); \
  if (dir.empty()) GTEST_SKIP() << ::scanloc::testing::kNoDatasets

// The laser's poses of a session's run folder (its trajectory.tum through the mounting its
// summary.json records): what relations between scans are scored on. Fails the test when the
// summary records no mounting.
std::vector<StampedPose> RunLaserPoses(const std::string& run_folder);

bool Contains(const std::string& text, const std::string& part);

// Writes `content` to `path` and returns the path.
std::string WriteText(const std::string& path, const std::string& content);

// The "real" scan of the refinement tests: `map` seen from the true posture over 720 beams, with
// Gaussian noise of sigma_m from a fixed seed.
LaserScan RealScan(const LineMap& map, const Pose2D& T_world_laser_true, double sigma_m);

// Calls `read` (a reader on `path`) and checks that it throws a ParseError at `line` whose message
// names the file and the line and contains `expected`.
void ExpectParseError(const std::function<void()>& read, const std::string& path, std::size_t line,
                      const std::string& expected);

// A fresh temporary directory for one test, removed when the test program ends.
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
