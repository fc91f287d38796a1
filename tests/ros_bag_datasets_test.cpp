// The ACES log converted to a ROS bag (scripts/make-bag.py: LaserScan, Odometry, tf_static) gives
// the CARMEN log's trajectory. The bag is written at test time from $SCANLOC_DATASETS/aces.clf.gz;
// the public logs are never committed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "run_scanloc.hpp"
#include "scanloc/io/ros_bag_source.hpp"
#include "scanloc/io/trajectory.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

constexpr char kPython[] = "/usr/bin/python3";  // Debian's, with python3-rosbag
constexpr char kScans[] = "200";

class RosBagDatasetsTest : public testing::TemporaryDirTest {};

TEST_F(RosBagDatasetsTest, AcesAsABagGivesTheCarmenLogsTrajectoryWithin1mm) {
  if (!RosBagSupported()) GTEST_SKIP() << "built without ROS bag support";
  const std::string datasets = testing::DatasetsDir();
  const std::string log = datasets + "/aces.clf.gz";
  if (datasets.empty() || !std::filesystem::exists(log))
    GTEST_SKIP() << "no aces.clf.gz in $SCANLOC_DATASETS (default ../shared/datasets)";
  const std::string bag = dir_ + "/aces.bag";
  const auto made =
      testing::RunCommand({kPython, std::string(SCANLOC_SOURCE_DIR) + "/scripts/make-bag.py", log,
                           bag, "--max-scans", kScans},
                          dir_);
  if (!made.exited || made.exit_code != 0)
    GTEST_SKIP() << "cannot write a bag (python3-rosbag and the msgs packages missing?): " << made;

  for (const auto& [input, run] :
       {std::pair{log, dir_ + "/carmen"}, std::pair{bag, dir_ + "/bag"}}) {
    const auto r = testing::RunScanloc(
        {"session", "--log", input, "--max-scans", kScans, "--out", run, "--quiet"}, dir_);
    ASSERT_TRUE(r.exited && r.exit_code == 0) << r;
  }
  const auto carmen = ReadTumTrajectory(dir_ + "/carmen/trajectory.tum");
  const auto from_bag = ReadTumTrajectory(dir_ + "/bag/trajectory.tum");
  ASSERT_EQ(carmen.size(), 200u);
  ASSERT_EQ(from_bag.size(), carmen.size());
  double max_position_m = 0.0, max_yaw_rad = 0.0, max_dt_s = 0.0;
  for (std::size_t i = 0; i < carmen.size(); ++i) {
    max_dt_s = std::max(max_dt_s, std::abs(carmen[i].timestamp_s - from_bag[i].timestamp_s));
    max_position_m = std::max(
        max_position_m, (carmen[i].pose.Translation() - from_bag[i].pose.Translation()).norm());
    max_yaw_rad = std::max(
        max_yaw_rad, std::abs(NormalizeAngle(carmen[i].pose.yaw_rad - from_bag[i].pose.yaw_rad)));
  }
  EXPECT_LE(max_dt_s, 1e-6);
  EXPECT_LE(max_position_m, 1e-3);  // identical at the time of writing (bearings recovered exactly)
  EXPECT_LE(max_yaw_rad, 1e-3);
  std::printf("ACES, first %s scans: bag vs CARMEN max %.3g m, %.3g rad, %.3g s\n", kScans,
              max_position_m, max_yaw_rad, max_dt_s);
}

}  // namespace
}  // namespace scanloc
