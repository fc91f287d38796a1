// The CARMEN reader on the forms real logs take beyond the benchmark ones: both PARAM forms and
// repeated parameters, other message types, a log's own no-return code, RAWLASER1, logs carrying
// several laser messages for the same scans, and timestamps that do not increase.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "scanloc/io/carmen_log.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/io/session_run.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

using testing::TemporaryDir;
using testing::WriteText;

constexpr double kTolerance = 1e-12;

std::string Write(const std::string& name, const std::string& content) {
  return WriteText(TemporaryDir() + "/" + name, content);
}

// A FLASER of the given ranges at odometry (x, 0, 0) and IPC timestamp t.
std::string Flaser(const std::vector<double>& ranges_m, double x_m, double t) {
  std::ostringstream line;
  line << "FLASER " << ranges_m.size();
  for (const double r : ranges_m) line << " " << r;
  line << " 0 0 0 " << x_m << " 0 0 " << t << " host " << t << "\n";
  return line.str();
}

// `scans` FLASERs of 181 beams at 5 m but every fourth beam at `code_m` (Örebro's no-return).
std::string SaturatedLog(std::size_t scans, double code_m) {
  std::string log;
  for (std::size_t s = 0; s < scans; ++s) {
    std::vector<double> ranges(181, 5.0);
    for (std::size_t b = 0; b < ranges.size(); b += 4) ranges[b] = code_m;
    log += Flaser(ranges, 0.1 * s, 1.0 + s);
  }
  return log;
}

std::vector<CarmenRecord> Lasers(CarmenReader& reader) {
  std::vector<CarmenRecord> lasers;
  for (CarmenRecord record; reader.Next(record);)
    if (record.kind == CarmenRecord::Kind::kLaser) lasers.push_back(record);
  return lasers;
}

// The JSON summary a session would write for a source read to its end.
nlohmann::json SummaryOf(IterationSource& source) {
  for (Iteration iteration; source.Next(iteration);) {
  }
  return SummaryJson(SessionRun{}, source);
}

TEST(CarmenRealLogs, ReadsTheLaserOffsetInTheSixFieldParamForm) {
  const std::string path =
      Write("six.clf", "PARAM robot_frontlaser_offset 0.1 1234.5 host 1234.6\n" +
                           Flaser({1, 2, 3, 4}, 0, 1.0));
  CarmenReader reader(path);
  EXPECT_EQ(Lasers(reader).size(), 1u) << "the log is read, not refused";
  EXPECT_NEAR(reader.mounting().T_robot_laser.x_m, 0.1, kTolerance);
}

TEST(CarmenRealLogs, AParameterSetTwiceBeforeTheFirstScanTakesTheLaterValue) {
  const std::string path = Write("twice.clf",
                                 "PARAM robot_frontlaser_offset 0.3 nohost 0\n"
                                 "PARAM robot_frontlaser_offset 0.04 1.0 host 1.0\n" +
                                     Flaser({1, 2, 3, 4}, 0, 1.0));
  CarmenReader reader(path);
  Lasers(reader);
  EXPECT_NEAR(reader.mounting().T_robot_laser.x_m, 0.04, kTolerance);
}

TEST(CarmenRealLogs, AParamOfAnyOtherFieldCountIsAParseErrorNamingBothForms) {
  const std::string path =
      Write("param7.clf", "ODOM 0 0 0 0 0 0 1 h 1\nPARAM robot_frontlaser_offset 0.1 1 h 1 x\n");
  testing::ExpectParseError(
      [&] {
        CarmenReader reader(path);
        Lasers(reader);
      },
      path, 2, "needs 5 fields (PARAM name value hostname timestamp) or 6");
}

TEST(CarmenRealLogs, OtherParametersOfAnyFormAreIgnored) {
  const std::string path = Write("other.clf",
                                 "PARAM laser_frontlaser_resolution 1 0.0 nohost 0\n"
                                 "PARAM robot_name my robot with spaces\n" +
                                     Flaser({1, 2, 3, 4}, 0, 1.0));
  CarmenReader reader(path);
  EXPECT_EQ(Lasers(reader).size(), 1u);
  EXPECT_TRUE(reader.skipped_messages().empty()) << "PARAM lines are not skipped messages";
}

TEST(CarmenRealLogs, UnknownMessagesAreSkippedAndCountedByTypeInTheSummary) {
  const std::string log = Flaser({1, 2, 3, 4}, 0, 1.0) + "NEFF 1 2 3\nTRUEPOS 0 0 0 1 1 1 1 h 1\n" +
                          Flaser({1, 2, 3, 4}, 0, 2.0) + "NEFF 4 5 6\nRAWLASER2 garbage\n";
  const std::string path = Write("unknown.clf", log);
  CarmenIterationSource source(path);
  const nlohmann::json summary = SummaryOf(source);
  EXPECT_EQ(summary["skipped_messages"],
            (nlohmann::json{{"NEFF", 2}, {"RAWLASER2", 1}, {"TRUEPOS", 1}}));
}

TEST(CarmenRealLogs, ALogsOwnSaturationCodeIsRecognisedAndItsReadingsCarryNoEcho) {
  const std::string path = Write("orebro_like.clf", SaturatedLog(30, 32.767));
  CarmenReader reader(path);
  ASSERT_TRUE(reader.recognised_no_return_m().has_value());
  EXPECT_NEAR(*reader.recognised_no_return_m(), 32.767, kTolerance);
  EXPECT_NEAR(reader.no_return_m(), 32.767, kTolerance);
  const std::vector<CarmenRecord> lasers = Lasers(reader);
  ASSERT_EQ(lasers.size(), 30u);
  EXPECT_FALSE(lasers[0].scan.IsValid(0)) << "32.767 is no return, not a phantom wall";
  EXPECT_TRUE(lasers[0].scan.IsValid(1));
  EXPECT_EQ(lasers[29].scan.CountValid(), 181u - 46u);

  CarmenIterationSource source(path);
  const nlohmann::json summary = SummaryOf(source);
  EXPECT_NEAR(summary["no_return_m"].get<double>(), 32.767, kTolerance);
  EXPECT_NEAR(summary["no_return_recognised_m"].get<double>(), 32.767, kTolerance);
}

TEST(CarmenRealLogs, TheNoReturnValueCanBeSetByHandOrItsRecognitionTurnedOff) {
  const std::string path = Write("orebro_like.clf", SaturatedLog(30, 32.767));
  CarmenOptions by_hand;
  by_hand.no_return_m = 20.0;
  CarmenReader given(path, by_hand);
  EXPECT_FALSE(given.recognised_no_return_m().has_value());
  EXPECT_NEAR(given.no_return_m(), 20.0, kTolerance);

  CarmenOptions off;
  off.detect_no_return = false;
  CarmenReader raw(path, off);
  EXPECT_FALSE(raw.recognised_no_return_m().has_value());
  EXPECT_NEAR(raw.no_return_m(), 50.0, kTolerance) << "max_range_m alone";
  EXPECT_TRUE(Lasers(raw)[0].scan.IsValid(0)) << "as the reader read Örebro before";
}

TEST(CarmenRealLogs, AFarMaximumReadOnceKeepsItsWallAndTheMaxRangeStands) {
  std::string log;
  for (std::size_t s = 0; s < 30; ++s) {
    std::vector<double> ranges(181, 5.0);
    if (s == 3) ranges[90] = 45.5;  // the one far reading
    log += Flaser(ranges, 0.1 * s, 1.0 + s);
  }
  CarmenReader reader(Write("far.clf", log));
  EXPECT_FALSE(reader.recognised_no_return_m().has_value());
  EXPECT_NEAR(reader.no_return_m(), 50.0, kTolerance);
  EXPECT_TRUE(Lasers(reader)[3].scan.IsValid(90));
}

TEST(CarmenRealLogs, ACodeAboveTheMaxRangeLeavesTheMaxRangeInForce) {
  CarmenReader reader(Write("intel_like.clf", SaturatedLog(30, 81.83)));
  ASSERT_TRUE(reader.recognised_no_return_m().has_value());
  EXPECT_NEAR(*reader.recognised_no_return_m(), 81.83, kTolerance);
  EXPECT_NEAR(reader.no_return_m(), 50.0, kTolerance);
}

// RAWLASER1 laser_type start_angle fov angular_resolution max_range accuracy remission_mode,
// 3 readings, 0 remissions, ipc_timestamp host logger_timestamp.
const std::string kRawLaser = "RAWLASER1 0 -0.5 1.0 0.5 8.0 0.01 0 3 1.0 2.0 8.0 0 ";

TEST(CarmenRealLogs, RawLaser1TakesItsLayoutFromTheMessageAndTheLatestOdom) {
  const std::string path = Write("raw.clf", kRawLaser + "10.0 host 10.0\n" +
                                                "ODOM 1 2 0.5 0.3 0 0 10.5 h 10.5\n"
                                                "ODOM 3 4 0.25 0.3 0 0 10.9 h 10.9\n" +
                                                kRawLaser + "11.0 host 11.0\n");
  CarmenReader reader(path);
  const std::vector<CarmenRecord> lasers = Lasers(reader);
  ASSERT_EQ(lasers.size(), 2u);
  EXPECT_FALSE(lasers[0].has_odometry) << "no ODOM before the first scan";
  const LaserScan& scan = lasers[1].scan;
  EXPECT_EQ(scan.layout.beam_count, 3u);
  EXPECT_NEAR(scan.layout.Bearing(0), -0.5, kTolerance);
  EXPECT_NEAR(scan.layout.Bearing(2), 0.5, kTolerance);
  EXPECT_NEAR(scan.layout.range_max_m, 8.0, kTolerance);
  EXPECT_FALSE(scan.IsValid(2)) << "a reading at max_range is a no-return";
  ASSERT_TRUE(lasers[1].has_odometry);
  EXPECT_NEAR(lasers[1].odometry.x_m, 3.0, kTolerance);
  EXPECT_NEAR(lasers[1].odometry.y_m, 4.0, kTolerance);
  EXPECT_NEAR(lasers[1].odometry.yaw_rad, 0.25, kTolerance);
  EXPECT_NEAR(lasers[1].timestamp_s, 11.0, kTolerance);

  CarmenIterationSource source(path);
  Iteration iteration;
  ASSERT_TRUE(source.Next(iteration));
  EXPECT_FALSE(iteration.odometry.has_value());
  ASSERT_TRUE(source.Next(iteration));
  ASSERT_TRUE(iteration.odometry.has_value());
  EXPECT_NEAR(iteration.odometry->x_m, 3.0, kTolerance);
}

TEST(CarmenRealLogs, ALaserResolutionOfZeroIsTakenFromTheFieldOfView) {
  const std::string path =
      Write("fov.clf", "RAWLASER1 0 -0.75 1.5 0 8.0 0.01 0 4 1 1 1 1 0 5.0 host 5.0\n");
  const LaserScan scan = ReadCarmenScan(path, 0);
  EXPECT_NEAR(scan.layout.angle_increment_rad, 0.5, kTolerance) << "fov / (n − 1)";
  EXPECT_NEAR(scan.layout.Bearing(3), 0.75, kTolerance);
}

TEST(CarmenRealLogs, ALogWithRobotLaser1AndFlaserIsReadThroughRobotLaser1Only) {
  // Each scan twice: as FLASER (the old message) and as ROBOTLASER1, and once more as RAWLASER1.
  std::string log;
  for (int s = 0; s < 3; ++s) {
    const std::string t = std::to_string(20 + s);
    log += Flaser({1, 2, 3}, s, 20 + s);
    log += "ROBOTLASER1 0 -0.5 1.0 0.5 8.0 0.01 0 3 1.0 2.0 3.0 0 0 0 0 " + std::to_string(s) +
           " 0 0 0.1 0 1 1 0 " + t + " host " + t + "\n";
    log += kRawLaser + t + " host " + t + "\n";
  }
  CarmenReader reader(Write("both.clf", log));
  const std::vector<CarmenRecord> lasers = Lasers(reader);
  ASSERT_EQ(lasers.size(), 3u) << "each scan once";
  EXPECT_NEAR(lasers[2].scan.layout.angle_increment_rad, 0.5, kTolerance) << "ROBOTLASER1's";
  EXPECT_NEAR(lasers[2].odometry.x_m, 2.0, kTolerance);
  EXPECT_EQ(reader.skipped_messages().at("FLASER"), 3u);
  EXPECT_EQ(reader.skipped_messages().at("RAWLASER1"), 3u);
}

TEST(CarmenRealLogs, ALaserOffsetChangedAfterTheFirstScanIsIgnoredAndCounted) {
  const std::string path = Write("late.clf", "PARAM robot_frontlaser_offset 0.2 nohost 0\n" +
                                                 Flaser({1, 2, 3, 4}, 0, 1.0) +
                                                 "PARAM robot_frontlaser_offset 0.2 nohost 0\n"
                                                 "PARAM robot_frontlaser_offset 0.5 nohost 0\n" +
                                                 Flaser({1, 2, 3, 4}, 0, 2.0));
  CarmenIterationSource source(path);
  const nlohmann::json summary = SummaryOf(source);
  EXPECT_EQ(summary["laser_offsets_ignored"], 1);
  EXPECT_NEAR(source.mounting().T_robot_laser.x_m, 0.2, kTolerance);
}

TEST(CarmenRealLogs, ZeroRepeatedAndBackwardTimestampsAreCountedAndEveryScanKept) {
  const std::string path =
      Write("times.clf", Flaser({1, 2}, 0, 0.0) + Flaser({1, 2}, 1, 0.0) + Flaser({1, 2}, 2, 5.0) +
                             Flaser({1, 2}, 3, 4.0) + Flaser({1, 2}, 4, 6.0));
  CarmenIterationSource source(path);
  std::vector<double> odometry_x;
  for (Iteration iteration; source.Next(iteration);) odometry_x.push_back(iteration.odometry->x_m);
  EXPECT_EQ(odometry_x, (std::vector<double>{0, 1, 2, 3, 4})) << "in log order";
  const nlohmann::json summary = SummaryJson(SessionRun{}, source);
  EXPECT_EQ(summary["timestamps_not_increasing"], 2) << "0 -> 0 repeated, 5 -> 4 backwards";
  EXPECT_EQ(summary["timestamps_zero"], 2);
}

}  // namespace
}  // namespace scanloc
