#include "test_support.hpp"

#include "scanloc/common/parse_error.hpp"
#include "scanloc/evaluation/relations_evaluation.hpp"
#include "scanloc/io/run_summary.hpp"

#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace scanloc::testing {

LineMap RectangleRoom(double width_m, double height_m) {
  LineMap map;
  map.segments = {{{0, 0}, {width_m, 0}},
                  {{width_m, 0}, {width_m, height_m}},
                  {{width_m, height_m}, {0, height_m}},
                  {{0, height_m}, {0, 0}}};
  return map;
}

LineMap Classroom() {
  LineMap map = RectangleRoom(6.3, 7.0);
  map.segments.push_back({{5.4, 6.0}, {6.0, 6.0}});
  map.segments.push_back({{6.0, 6.0}, {6.0, 6.6}});
  return map;
}

LineMap RingBuilding() {
  LineMap map;
  auto box = [&map](double x0, double y0, double x1, double y1) {
    map.segments.push_back({{x0, y0}, {x1, y0}});
    map.segments.push_back({{x1, y0}, {x1, y1}});
    map.segments.push_back({{x1, y1}, {x0, y1}});
    map.segments.push_back({{x0, y1}, {x0, y0}});
  };
  box(0.0, 0.0, 24.0, 16.0);  // outer walls
  box(4.0, 4.0, 20.0, 12.0);  // the block
  box(1.0, 1.0, 1.6, 1.5);    // boxes in the corridor, each corner different
  box(9.0, 0.0, 9.8, 0.7);
  box(15.0, 3.2, 16.5, 4.0);
  box(22.8, 7.0, 24.0, 8.2);
  box(20.0, 13.0, 20.6, 13.4);
  box(12.0, 15.2, 12.5, 16.0);
  box(6.0, 12.0, 6.9, 12.6);
  box(0.0, 9.0, 0.5, 10.5);
  box(4.0, 6.0, 3.4, 6.8);
  return map;
}

LaserSimulatorOptions RingBuildingLaser() {
  LaserSimulatorOptions laser;
  laser.beam_count = 181;
  laser.fov_rad = M_PI;
  laser.range_max_m = 12.0;
  laser.reliable_range_m = 12.0;
  laser.range_noise_m = 0.01;
  laser.range_noise_per_m = 0.0;
  return laser;
}

LineMap SmallRoomWithL() {
  LineMap map = RectangleRoom(8.0, 6.0);
  map.segments.push_back({{6.0, 4.0}, {7.0, 4.0}});
  map.segments.push_back({{7.0, 4.0}, {7.0, 5.0}});
  return map;
}

LaserScan NoisyScan(const LineMap& map, const Pose2D& T_world_laser, std::size_t beams,
                    double sigma_m, unsigned seed) {
  const ScanLayout layout = MakeLayout(beams, 2.0 * M_PI, 20.0);
  LaserScan scan = ScanFromSimulation(SimulateFromLines(map, layout, T_world_laser));
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma_m);
  if (sigma_m > 0.0)
    for (double& range : scan.ranges_m)
      if (range > 0.0) range += noise(rng);
  return scan;
}

LaserScan ScanFromSimulation(const SimulatedScan& simulated) {
  LaserScan scan;
  scan.layout = simulated.layout;
  scan.ranges_m = simulated.ranges_m;
  return scan;
}

std::string DatasetsDir() {
  const char* env = std::getenv("SCANLOC_DATASETS");
  const std::string dir = env != nullptr && *env != '\0' ? env : SCANLOC_DEFAULT_DATASETS;
  return std::filesystem::is_directory(dir) ? dir : "";
}

namespace {

// Copies the public log `log` to `path`, gzip compressed, a line at a time as its fields:
// `edit` may change them and returns false to leave the line out.
void CopyLog(const std::string& log, const std::string& path,
             const std::function<bool(std::vector<std::string>&)>& edit) {
  gzFile in = gzopen((testing::DatasetsDir() + "/" + log + ".clf.gz").c_str(), "rb");
  gzFile out = gzopen(path.c_str(), "wb");
  ASSERT_TRUE(in != nullptr && out != nullptr);
  std::vector<char> buffer(1 << 16);
  while (gzgets(in, buffer.data(), static_cast<int>(buffer.size())) != nullptr) {
    std::istringstream line(buffer.data());
    std::vector<std::string> fields{std::istream_iterator<std::string>(line), {}};
    if (!edit(fields)) continue;
    std::string text;
    for (const std::string& field : fields) text += (text.empty() ? "" : " ") + field;
    text += "\n";
    gzwrite(out, text.data(), static_cast<unsigned>(text.size()));
  }
  gzclose(in);
  gzclose(out);
}

}  // namespace

void WriteWithZeroedOdometry(const std::string& log, const std::string& path) {
  CopyLog(log, path, [](std::vector<std::string>& fields) {
    if (fields.size() > 2 && fields[0] == "FLASER") {
      const std::size_t beams = std::stoul(fields[1]);
      for (std::size_t f = 2 + beams; f < 8 + beams && f < fields.size(); ++f) fields[f] = "0";
    }
    return true;
  });
}

void WriteSparse(const std::string& log, const std::string& path) {
  std::optional<Pose2D> kept;
  CopyLog(log, path, [&](std::vector<std::string>& fields) {
    if (fields.size() <= 2 || fields[0] != "FLASER") return true;
    const std::size_t odometry = 2 + std::stoul(fields[1]) + 3;  // odom_x odom_y odom_theta
    if (odometry + 2 >= fields.size()) {
      ADD_FAILURE() << "a FLASER line of " << log << " without its odometry";
      return true;
    }
    const Pose2D pose{std::stod(fields[odometry]), std::stod(fields[odometry + 1]),
                      std::stod(fields[odometry + 2])};
    if (kept && !SparseKeeps(Between(*kept, pose))) return false;
    kept = pose;
    return true;
  });
}

bool SparseKeeps(const Pose2D& odometry_step) {
  return std::hypot(odometry_step.x_m, odometry_step.y_m) >= kSparseKeepM ||
         std::abs(odometry_step.yaw_rad) >= kSparseKeepRad;
}

namespace {

// The directories TemporaryDir() made, removed when the test program ends: a test that writes a
// file or two into one leaves nothing behind in the system's temporary folder.
class MadeDirectories {
 public:
  ~MadeDirectories() {
    if (::getpid() != owner_) return;  // not in a forked child
    for (const std::string& dir : dirs_) {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  }
  void Add(std::string dir) {
    std::lock_guard<std::mutex> lock(mutex_);
    dirs_.push_back(std::move(dir));
  }

 private:
  const pid_t owner_ = ::getpid();
  std::mutex mutex_;
  std::vector<std::string> dirs_;
};

MadeDirectories& Made() {
  static MadeDirectories made;
  return made;
}

}  // namespace

std::string TemporaryDir() {
  auto base = std::filesystem::temp_directory_path() / "scanloc-test-XXXXXX";
  std::string pattern = base.string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  Made().Add(pattern);
  return pattern;
}

void TemporaryDirTest::TearDown() {
  std::filesystem::remove_all(dir_);
}

std::string TemporaryDirTest::Write(const std::string& name, const std::string& content) const {
  const std::string path = dir_ + "/" + name;
  std::ofstream(path) << content;
  return path;
}

std::vector<StampedPose> RunLaserPoses(const std::string& run_folder) {
  const std::optional<LaserMounting> mounting = ReadRunMounting(run_folder + "/summary.json");
  EXPECT_TRUE(mounting.has_value()) << run_folder << "/summary.json records no mounting";
  return LaserPoses(ReadTumTrajectory(run_folder + "/trajectory.tum"),
                    mounting.value_or(LaserMounting{}));
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string WriteText(const std::string& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

LaserScan RealScan(const LineMap& map, const Pose2D& T_world_laser_true, double sigma_m) {
  constexpr unsigned kNoiseSeed = 20240611;
  return NoisyScan(map, T_world_laser_true, 720, sigma_m, kNoiseSeed);
}

void ExpectParseError(const std::function<void()>& read, const std::string& path, std::size_t line,
                      const std::string& expected) {
  try {
    read();
    ADD_FAILURE() << "no ParseError for " << path;
  } catch (const ParseError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.file(), path);
    EXPECT_EQ(error.line(), line) << message;
    EXPECT_TRUE(Contains(message, path + ":" + std::to_string(line) + ":")) << message;
    EXPECT_TRUE(Contains(message, expected)) << message;
  }
}

}  // namespace scanloc::testing
