#include "scanloc/io/ros_bag_source.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "scanloc/io/sequence_sources.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

const std::string kClassroomBag =
    std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/classroom.bag";
const std::string kClassroomSequence =
    std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/classroom.seq.jsonl";
const std::string kTfOdometryBag = std::string(SCANLOC_SOURCE_DIR) + "/tests/data/tf_odometry.bag";

// datasets/classroom/classroom.bag: the first 40 scans of the sequence (scripts/make-bag.py).
constexpr std::size_t kClassroomBagScans = 40;

#define SKIP_WITHOUT_ROSBAG() \
  if (!RosBagSupported()) GTEST_SKIP() << "built without ROS bag support"

TEST(RosBagSource, ClassroomBagGivesTheSequencesScansOdometryAndMounting) {
  SKIP_WITHOUT_ROSBAG();
  auto bag = OpenIterationSource(kClassroomBag);  // a bag, told by its content
  ASSERT_NE(dynamic_cast<RosBagIterationSource*>(bag.get()), nullptr);
  SequenceFileSource sequence(kClassroomSequence);
  EXPECT_NEAR(bag->mounting().T_robot_laser.x_m, 0.15, 1e-12);
  EXPECT_NEAR(bag->mounting().T_robot_laser.y_m, 0.0, 1e-12);
  EXPECT_NEAR(bag->mounting().T_robot_laser.yaw_rad, 0.0, 1e-12);
  Iteration from_bag, expected;
  std::size_t count = 0;
  while (bag->Next(from_bag)) {
    ASSERT_TRUE(sequence.Next(expected));
    ++count;
    EXPECT_NEAR(from_bag.timestamp_s, expected.timestamp_s, 1e-6);
    const LaserScan& a = from_bag.scan;
    const LaserScan& b = expected.scan;
    ASSERT_EQ(a.size(), b.size());
    // float32 in the bag, recovered to the double of a full turn in 2,400 steps
    EXPECT_EQ(a.layout.angle_min_rad, b.layout.angle_min_rad);
    EXPECT_EQ(a.layout.angle_increment_rad, b.layout.angle_increment_rad);
    EXPECT_EQ(a.layout.range_max_m, b.layout.range_max_m);
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a.IsValid(i), b.IsValid(i)) << "beam " << i;
      // Millimetre ranges come back exactly from their float32 (shortest decimal form).
      if (b.IsValid(i)) {
        ASSERT_EQ(a.ranges_m[i], b.ranges_m[i]) << "beam " << i;
      }
    }
    ASSERT_TRUE(from_bag.odometry && expected.odometry);
    EXPECT_NEAR(from_bag.odometry->x_m, expected.odometry->x_m, 1e-12);
    EXPECT_NEAR(from_bag.odometry->y_m, expected.odometry->y_m, 1e-12);
    EXPECT_NEAR(from_bag.odometry->yaw_rad, expected.odometry->yaw_rad, 1e-12);
  }
  EXPECT_EQ(count, kClassroomBagScans);
}

TEST(RosBagSource, OdometryFromTfIsInterpolatedToEachScanStamp) {
  SKIP_WITHOUT_ROSBAG();
  RosBagIterationSource bag(kTfOdometryBag);  // no /odom topic: odometry from /tf
  EXPECT_EQ(bag.OdometrySource(), "tf odom → base_link");
  // Samples at 0.5, 1.5, 2.5, 3.5 s: (0,0,0), (1,0,0.2), (2,1,0.4), (3,1,0.4); scans halfway.
  const Pose2D expected[] = {{0.5, 0.0, 0.1}, {1.5, 0.5, 0.3}, {2.5, 1.0, 0.4}};
  Iteration iteration;
  for (const Pose2D& pose : expected) {
    ASSERT_TRUE(bag.Next(iteration));
    ASSERT_TRUE(iteration.odometry);
    EXPECT_NEAR(iteration.odometry->x_m, pose.x_m, 1e-9);
    EXPECT_NEAR(iteration.odometry->y_m, pose.y_m, 1e-9);
    EXPECT_NEAR(iteration.odometry->yaw_rad, pose.yaw_rad, 1e-9);
  }
  EXPECT_FALSE(bag.Next(iteration));
  EXPECT_DOUBLE_EQ(bag.Progress(), 1.0);
}

TEST(RosBagSource, MountingComposesTheTfStaticChainFromBaseLinkToTheScanFrame) {
  SKIP_WITHOUT_ROSBAG();
  RosBagIterationSource bag(kTfOdometryBag);
  // (0.1, 0, 0) · (0.05, 0.02, π/2)
  EXPECT_NEAR(bag.mounting().T_robot_laser.x_m, 0.15, 1e-9);
  EXPECT_NEAR(bag.mounting().T_robot_laser.y_m, 0.02, 1e-9);
  EXPECT_NEAR(bag.mounting().T_robot_laser.yaw_rad, M_PI / 2, 1e-9);
  RosBagOptions options;
  options.mounting = Pose2D(0.3, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(RosBagIterationSource(kTfOdometryBag, options).mounting().T_robot_laser.x_m,
                   0.3);
}

TEST(RosBagSource, DecreasingBearingsAreReversedAndNoEchoBeamsInvalid) {
  SKIP_WITHOUT_ROSBAG();
  RosBagIterationSource bag(kTfOdometryBag);
  Iteration iteration;
  ASSERT_TRUE(bag.Next(iteration));
  const LaserScan& scan = iteration.scan;
  // Written as angle_min 0.5, increment -0.25, ranges 1.25 inf nan 30 0.05 3.45 (min 0.1, max 20).
  ASSERT_EQ(scan.size(), 6u);
  EXPECT_DOUBLE_EQ(scan.layout.angle_min_rad, -0.75);
  EXPECT_DOUBLE_EQ(scan.layout.angle_increment_rad, 0.25);
  EXPECT_EQ(scan.ranges_m[0], 3.45);  // the last beam first, at its decimal value
  EXPECT_TRUE(scan.IsValid(0));
  for (std::size_t i = 1; i <= 4; ++i) EXPECT_FALSE(scan.IsValid(i)) << "beam " << i;
  EXPECT_EQ(scan.ranges_m[5], 1.25);
  EXPECT_TRUE(scan.IsValid(5));
  ASSERT_EQ(scan.reflectance.size(), 6u);
  EXPECT_EQ(scan.reflectance[0], 60.0);
  EXPECT_DOUBLE_EQ(iteration.timestamp_s, 1.0);
}

TEST(RosBagSource, MissingScanTopicNamesTheBagAndItsLaserScanTopics) {
  SKIP_WITHOUT_ROSBAG();
  RosBagOptions options;
  options.scan_topic = "/base_scan";
  try {
    RosBagIterationSource bag(kTfOdometryBag, options);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("tf_odometry.bag"), std::string::npos) << message;
    EXPECT_NE(message.find("/base_scan"), std::string::npos) << message;
    EXPECT_NE(message.find("LaserScan topics in the bag: /scan"), std::string::npos) << message;
  }
}

TEST(RosBagSource, WrongBaseFrameIsAnErrorNamingTheFrames) {
  SKIP_WITHOUT_ROSBAG();
  RosBagOptions options;
  options.base_frame = "base_footprint";
  EXPECT_THROW(RosBagIterationSource(kTfOdometryBag, options), std::runtime_error);
}

TEST(RosBagSource, UnusableScanLayoutIsAnErrorNamingTheBagAndMessage) {
  SKIP_WITHOUT_ROSBAG();
  RosBagIterationSource bag(SCANLOC_SOURCE_DIR "/tests/data/zero_increment.bag");
  Iteration iteration;
  try {
    bag.Next(iteration);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("zero_increment.bag:/scan#0"), std::string::npos)
        << e.what();
  }
}

TEST(RosBagSource, TruncatedBagIsAnErrorNamingIt) {
  SKIP_WITHOUT_ROSBAG();
  const std::string path = testing::TemporaryDir() + "/truncated.bag";
  {
    std::ifstream in(kClassroomBag, std::ios::binary);
    std::string bytes(20000, '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    std::ofstream(path, std::ios::binary) << bytes;
  }
  try {
    RosBagIterationSource bag(path);
    Iteration iteration;
    while (bag.Next(iteration)) {
    }
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated.bag"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace scanloc
