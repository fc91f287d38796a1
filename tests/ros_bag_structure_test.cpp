// A ROS bag's structure and messages checked before rosbag and roscpp believe their lengths
// (src/io/ros_bag_structure.cpp): the fuzz seeds (plain, bz2 and lz4 chunks, odometry from /odom
// and /tf) read; the fuzzer's 4 GB header, a header length patched by hand and a LaserScan whose
// ranges count exceeds its bytes are refused with where and what was expected, and so is the
// fuzzer's static transform with a NaN (C12).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "scanloc/io/ros_bag_source.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

const std::string kSeeds = std::string(SCANLOC_SOURCE_DIR) + "/fuzz/corpus/ros_bag/";

#define SKIP_WITHOUT_ROSBAG() \
  if (!RosBagSupported()) GTEST_SKIP() << "built without ROS bag support"

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

std::size_t ReadAll(const std::string& path) {
  RosBagIterationSource source(path, RosBagOptions{});
  Iteration iteration;
  std::size_t scans = 0;
  while (source.Next(iteration)) ++scans;
  return scans;
}

// The error reading `path` gives, or "" when it reads.
std::string ErrorOf(const std::string& path) {
  try {
    ReadAll(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

class RosBagStructureTest : public testing::TemporaryDirTest {};

TEST_F(RosBagStructureTest, TheSeedBagsReadWithEveryCompressionAndOdometrySource) {
  SKIP_WITHOUT_ROSBAG();
  for (const char* seed :
       {"tiny-topic-none.bag", "tiny-topic-bz2.bag", "tiny-topic-lz4.bag", "tiny-tf-none.bag"}) {
    SCOPED_TRACE(seed);
    EXPECT_EQ(ReadAll(kSeeds + seed), 3u);
  }
}

TEST_F(RosBagStructureTest, AConnectionHeaderAnnouncing4GBIsRefusedWithItsByte) {
  SKIP_WITHOUT_ROSBAG();
  const std::string error = ErrorOf(std::string(SCANLOC_SOURCE_DIR) +
                                    "/fuzz/crashes/ros_bag/"
                                    "connection-header-length-makes-rosbag-allocate-4-GB.bag");
  EXPECT_TRUE(testing::Contains(error, "at byte 15096: expected a record op")) << error;
}

TEST_F(RosBagStructureTest, ANaNInTheStaticTransformToTheLaserIsRefusedWithItsFrames) {
  SKIP_WITHOUT_ROSBAG();
  const std::string error = ErrorOf(std::string(SCANLOC_SOURCE_DIR) +
                                    "/fuzz/crashes/ros_bag/"
                                    "tf-static-nan-makes-a-non-finite-mounting.bag");
  EXPECT_TRUE(testing::Contains(error,
                                "/tf_static's transform from 'base_link' to 'laser': "
                                "expected a finite pose"))
      << error;
}

TEST_F(RosBagStructureTest, ARecordHeaderLengthBeyondTheFileIsRefused) {
  SKIP_WITHOUT_ROSBAG();
  std::string bag = Bytes(kSeeds + "tiny-topic-none.bag");
  const std::uint32_t huge = 0xFFFFFFFFu;
  std::memcpy(&bag[13], &huge, 4);  // the bag header record's header length
  const std::string error = ErrorOf(Write("huge-header.bag", bag));
  EXPECT_TRUE(testing::Contains(error, "at byte 13: expected a record header of at most 1 MiB"))
      << error;
}

TEST_F(RosBagStructureTest, ALaserScanAnnouncingMoreRangesThanItsBytesIsRefused) {
  SKIP_WITHOUT_ROSBAG();
  std::string bag = Bytes(kSeeds + "tiny-topic-none.bag");
  // The first scan's ranges: a count of 16, then 1.0f.
  const std::string ranges("\x10\x00\x00\x00\x00\x00\x80\x3f", 8);
  const std::size_t at = bag.find(ranges);
  ASSERT_NE(at, std::string::npos);
  const std::uint32_t count = 0x7FFFFFFFu;
  std::memcpy(&bag[at], &count, 4);
  const std::string error = ErrorOf(Write("many-ranges.bag", bag));
  EXPECT_TRUE(testing::Contains(error, "malformed sensor_msgs/LaserScan: ranges of 8589934588"))
      << error;
}

}  // namespace
}  // namespace scanloc
