#include "scanloc/io/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "scanloc/common/parse_error.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

constexpr double kTimestampTolerance = 1e-6;  // the writer's microsecond resolution
constexpr double kPositionTolerance = 1e-6;   // micrometres
constexpr double kYawTolerance = 1e-8;        // nine decimals of the quaternion

using testing::WriteText;

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The message of the ParseError that `read` throws, or "" when none is thrown.
template <typename Read>
std::string ParseErrorMessage(Read read) {
  try {
    read();
  } catch (const ParseError& error) {
    return error.what();
  }
  return "";
}

TEST(Trajectory, TumRoundTripKeepsTimestampsPositionsAndYaw) {
  const std::vector<StampedPose> poses = {
      {976052905.167303, Pose2D(1.25, -2.5, 0.0)},
      {976052890.244111, Pose2D(-13.123456, 40.5, M_PI)},  // out of time order, as in Intel
      {1.5, Pose2D(0.0, 0.0, -3.0)},
      {2.0, Pose2D(1e3, -1e3, 1.0)},
  };
  const std::string path = testing::TemporaryDir() + "/trajectory.tum";
  WriteTumTrajectory(path, poses);
  const std::vector<StampedPose> read = ReadTumTrajectory(path);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(read[i].timestamp_s, poses[i].timestamp_s, kTimestampTolerance) << i;
    EXPECT_NEAR(read[i].pose.x_m, poses[i].pose.x_m, kPositionTolerance) << i;
    EXPECT_NEAR(read[i].pose.y_m, poses[i].pose.y_m, kPositionTolerance) << i;
    EXPECT_NEAR(NormalizeAngle(read[i].pose.yaw_rad - poses[i].pose.yaw_rad), 0.0, kYawTolerance)
        << i;
  }
}

TEST(Trajectory, TumLinesHoldTimeXyzAndAYawQuaternion) {
  const std::string path = testing::TemporaryDir() + "/trajectory.tum";
  WriteTumTrajectory(path, {{976052905.167303, Pose2D(1.0, 2.0, 1.0)}});
  // sin(0.5) = 0.4794255386, cos(0.5) = 0.8775825619.
  EXPECT_EQ(ReadText(path),
            "# timestamp x y z qx qy qz qw\n"
            "976052905.167303 1.000000 2.000000 0 0 0 0.479425539 0.877582562\n");
}

TEST(Trajectory, WriteReplacesTheFileWholeAndLeavesNoTemporary) {
  const std::string dir = testing::TemporaryDir();
  const std::string path = dir + "/trajectory.tum";
  WriteTumTrajectory(path, {{1.0, Pose2D(1, 2, 0)}, {2.0, Pose2D(3, 4, 0)}});
  WriteTumTrajectory(path, {{5.0, Pose2D(5, 6, 0)}});
  const std::vector<StampedPose> read = ReadTumTrajectory(path);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_NEAR(read[0].timestamp_s, 5.0, kTimestampTolerance);

  // A non-finite pose is a broken contract: nothing is written, the old file stays.
  EXPECT_THROW(WriteTumTrajectory(path, {{6.0, Pose2D(std::nan(""), 0, 0)}}),
               std::invalid_argument);
  EXPECT_EQ(ReadTumTrajectory(path).size(), 1u);
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 1u);
}

TEST(Trajectory, TumReaderSkipsCommentsAndNormalisesTheQuaternion) {
  const std::string path = WriteText(testing::TemporaryDir() + "/other.tum",
                                     "# from another tool\n"
                                     "\n"
                                     "10.0 1 2 0 0 0 0 2\n"  // scaled identity
                                     "11.0 1 2 0.5 0 0 1.414213562 1.414213562\n"   // 90°, scaled
                                     "12.0 3 4 0 0 0 -0.707106781 0.707106781\n");  // -90°
  const std::vector<StampedPose> poses = ReadTumTrajectory(path);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_NEAR(poses[0].pose.yaw_rad, 0.0, kYawTolerance);
  EXPECT_NEAR(poses[1].pose.yaw_rad, M_PI / 2, kYawTolerance);
  EXPECT_NEAR(poses[2].pose.yaw_rad, -M_PI / 2, kYawTolerance);
  EXPECT_NEAR(poses[2].pose.x_m, 3.0, kPositionTolerance);
  EXPECT_NEAR(poses[2].timestamp_s, 12.0, kTimestampTolerance);
}

TEST(Trajectory, TumReaderErrorsNameFileLineAndExpectation) {
  const std::string dir = testing::TemporaryDir();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"1.0 1 2 0 0 0 0", "8 fields"},
      {"1.0 1 two 0 0 0 0 1", "'two'"},
      {"1.0 1 2 0 0 0 0 0", "non-zero quaternion"},
      {"inf 1 2 0 0 0 0 1", "timestamp"},
  };
  for (const auto& [line, expected] : cases) {
    const std::string path = WriteText(dir + "/bad.tum", "# header\n1.0 1 2 0 0 0 0 1\n" + line);
    const std::string message = ParseErrorMessage([&] { ReadTumTrajectory(path); });
    EXPECT_NE(message.find("bad.tum:3:"), std::string::npos) << line << " -> " << message;
    EXPECT_NE(message.find(expected), std::string::npos) << line << " -> " << message;
  }
}

TEST(Trajectory, CorrectedPosesKeepFileOrder) {
  const std::string path = WriteText(testing::TemporaryDir() + "/x.corrected-poses.txt",
                                     "976052892.442400 0.68231 -0.100086 -0.938803\n"
                                     "976052890.244111 0.600266 -0.0320327 -0.354665\n");
  const std::vector<StampedPose> poses = ReadCorrectedPoses(path);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_NEAR(poses[0].timestamp_s, 976052892.4424, kTimestampTolerance);
  EXPECT_NEAR(poses[0].pose.x_m, 0.68231, kPositionTolerance);
  EXPECT_NEAR(poses[0].pose.y_m, -0.100086, kPositionTolerance);
  EXPECT_NEAR(poses[0].pose.yaw_rad, -0.938803, kYawTolerance);
  EXPECT_NEAR(poses[1].timestamp_s, 976052890.244111, kTimestampTolerance);
}

TEST(Trajectory, CorrectedPosesErrorsNameFileAndLine) {
  const std::string path =
      WriteText(testing::TemporaryDir() + "/x.corrected-poses.txt", "1.0 0 0 0\n2.0 0 0\n");
  const std::string message = ParseErrorMessage([&] { ReadCorrectedPoses(path); });
  EXPECT_NE(message.find("x.corrected-poses.txt:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("4 fields"), std::string::npos) << message;
}

TEST(Trajectory, ReferencePosesAreReadInEitherFormatToTheSamePoses) {
  const std::string dir = testing::TemporaryDir();
  const std::string corrected =
      WriteText(dir + "/a.txt", "# t x y theta\n1.5 2 3 0.5\n2.5 -1 0.25 -0.5\n");
  const std::vector<StampedPose> written = ReadCorrectedPoses(corrected);
  WriteTumTrajectory(dir + "/a.tum", written);
  for (const std::string& path : {corrected, dir + "/a.tum"}) {
    const std::vector<StampedPose> poses = ReadReferencePoses(path);
    ASSERT_EQ(poses.size(), 2u) << path;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      EXPECT_NEAR(poses[i].timestamp_s, written[i].timestamp_s, kTimestampTolerance) << path;
      EXPECT_NEAR(poses[i].pose.x_m, written[i].pose.x_m, kPositionTolerance) << path;
      EXPECT_NEAR(poses[i].pose.y_m, written[i].pose.y_m, kPositionTolerance) << path;
      EXPECT_NEAR(poses[i].pose.yaw_rad, written[i].pose.yaw_rad, kYawTolerance) << path;
    }
  }
}

TEST(Trajectory, ReferencePosesOfNeitherOrOfMixedFormatsAreRefusedWithTheirLine) {
  const std::string dir = testing::TemporaryDir();
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"1.0 0 0 0 0\n", "r.txt:1:", "4 fields 'timestamp x y theta' or 8 fields"},
      {"1.0 0 0 0\n2.0 0 0 0 0 0 0 1\n", "r.txt:2:", "expected 4 fields"},
      {"1.0 0 0 0 0 0 0 1\n2.0 0 0 0\n", "r.txt:2:", "expected 8 fields"},
  };
  for (const auto& [text, where, expected] : cases) {
    const std::string path = WriteText(dir + "/r.txt", text);
    const std::string message = ParseErrorMessage([&] { ReadReferencePoses(path); });
    EXPECT_NE(message.find(where), std::string::npos) << text << " -> " << message;
    EXPECT_NE(message.find(expected), std::string::npos) << text << " -> " << message;
  }
}

TEST(Trajectory, MissingFilesThrowRuntimeErrorWithThePath) {
  const std::string path = testing::TemporaryDir() + "/absent.txt";
  for (auto read : {&ReadTumTrajectory, &ReadCorrectedPoses, &ReadReferencePoses}) {
    try {
      read(path);
      ADD_FAILURE() << "expected std::runtime_error";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
  }
}

TEST(TrajectoryDatasets, CorrectedPosesHaveTheDocumentedCounts) {
  SCANLOC_REQUIRE_DATASETS(dir);
  EXPECT_EQ(ReadCorrectedPoses(dir + "/intel.corrected-poses.txt").size(), 910u);
  EXPECT_EQ(ReadCorrectedPoses(dir + "/aces.corrected-poses.txt").size(), 440u);
  EXPECT_EQ(ReadCorrectedPoses(dir + "/fr079.corrected-poses.txt").size(), 4791u);
}

}  // namespace
}  // namespace scanloc
