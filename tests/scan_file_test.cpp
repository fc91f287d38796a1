#include "scanloc/io/scan_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/common/parse_error.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The first bearing and step are written with 15 significant digits.
constexpr double kAngleTolerance = 1e-13;

class ScanFileTest : public testing::TemporaryDirTest {
 protected:
  // Reads `content` as a scan file and checks that it fails with a ParseError at `line` whose
  // message names the file and line and contains `expected`.
  void ExpectParseError(const std::string& content, std::size_t line,
                        const std::string& expected) const {
    const std::string path = Write("bad.scan", content);
    SCOPED_TRACE(content);
    testing::ExpectParseError([&] { ReadScanFile(path); }, path, line, expected);
  }
};

// Eight beams over a full turn: three valid ranges, and the four ways of saying "no echo".
LaserScan EightBeamScan() {
  LaserScan scan;
  scan.layout = MakeLayout(8, 2.0 * M_PI, 20.0);
  scan.layout.range_min_m = 0.1;
  scan.timestamp_s = 1234.5625;
  scan.ranges_m = {1.25, kNaN, -1.0, 3.5, kInfinity, 12.3456, 0.05, 25.0};
  return scan;
}

void ExpectSameLayout(const ScanLayout& actual, const ScanLayout& expected) {
  EXPECT_EQ(actual.beam_count, expected.beam_count);
  EXPECT_NEAR(actual.angle_min_rad, expected.angle_min_rad, kAngleTolerance);
  EXPECT_NEAR(actual.angle_increment_rad, expected.angle_increment_rad, kAngleTolerance);
  EXPECT_DOUBLE_EQ(actual.range_min_m, expected.range_min_m);
  EXPECT_DOUBLE_EQ(actual.range_max_m, expected.range_max_m);
}

// Valid ranges keep their value; invalid ones stay invalid (NaN and -1 keep their coding).
void ExpectSameRanges(const LaserScan& actual, const LaserScan& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(actual.IsValid(i), expected.IsValid(i)) << "beam " << i;
    if (std::isnan(expected.ranges_m[i]))
      EXPECT_TRUE(std::isnan(actual.ranges_m[i])) << "beam " << i;
    else
      EXPECT_DOUBLE_EQ(actual.ranges_m[i], expected.ranges_m[i]) << "beam " << i;
  }
}

const std::string kHeader =
    "scanloc_scan 1\n"
    "beams 3\n"
    "angle_min_rad -0.5\n"
    "angle_increment_rad 0.5\n";

TEST_F(ScanFileTest, RoundTripKeepsLayoutTimestampAndRangesWithoutReflectance) {
  const LaserScan scan = EightBeamScan();
  const std::string path = dir_ + "/scan.scan";
  WriteScanFile(scan, path);
  const LaserScan read = ReadScanFile(path);
  ExpectSameLayout(read.layout, scan.layout);
  EXPECT_DOUBLE_EQ(read.timestamp_s, scan.timestamp_s);
  ExpectSameRanges(read, scan);
  EXPECT_TRUE(read.reflectance.empty());
  EXPECT_EQ(read.CountValid(), 3u);
}

TEST_F(ScanFileTest, RoundTripKeepsReflectance) {
  LaserScan scan = EightBeamScan();
  scan.reflectance = {0.5, 0.0, 0.0, 0.75, 0.0, 0.125, 1.0, 0.0};
  const std::string path = dir_ + "/scan.scan";
  WriteScanFile(scan, path);
  const LaserScan read = ReadScanFile(path);
  ExpectSameRanges(read, scan);
  EXPECT_EQ(read.reflectance, scan.reflectance);
}

TEST_F(ScanFileTest, RoundTripOfManyBeamsSpansSeveralLinesPerBlock) {
  // 2,400 beams are written ten per line: the reader must collect them across lines.
  LaserScan scan;
  scan.layout = MakeLayout(2400, 2.0 * M_PI, 20.0);
  for (std::size_t i = 0; i < 2400; ++i)
    scan.ranges_m.push_back(i % 7 == 0 ? -1.0 : 1.0 + i / 1000.0);
  const std::string path = dir_ + "/big.scan";
  WriteScanFile(scan, path);
  const LaserScan read = ReadScanFile(path);
  ExpectSameLayout(read.layout, scan.layout);
  ExpectSameRanges(read, scan);
}

// Written with too few digits, 19.9999996 would become "20", the maximum range, where there is
// no echo: the writer keeps every digit a double needs.
TEST_F(ScanFileTest, ValidRangeJustBelowTheMaximumStaysValidAfterRoundTrip) {
  LaserScan scan;
  scan.layout = MakeLayout(2, M_PI, 20.0);
  scan.ranges_m = {19.9999996, 1.0 / 3.0};
  ASSERT_TRUE(scan.IsValid(0));
  const std::string path = dir_ + "/edge.scan";
  WriteScanFile(scan, path);
  const LaserScan read = ReadScanFile(path);
  EXPECT_TRUE(read.IsValid(0));
  EXPECT_EQ(read.ranges_m, scan.ranges_m);
}

TEST_F(ScanFileTest, WriteLeavesOnlyTheTargetFileInTheDirectory) {
  const std::string path = dir_ + "/scan.scan";
  WriteScanFile(EightBeamScan(), path);
  WriteScanFile(EightBeamScan(), path);  // overwriting too
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir_))
    names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"scan.scan"});
}

TEST_F(ScanFileTest, InconsistentScanIsRefusedAndNothingIsWritten) {
  LaserScan scan = EightBeamScan();
  scan.ranges_m.pop_back();
  EXPECT_THROW(WriteScanFile(scan, dir_ + "/scan.scan"), std::invalid_argument);
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

TEST_F(ScanFileTest, WriteIntoMissingDirectoryThrowsRuntimeError) {
  EXPECT_THROW(WriteScanFile(EightBeamScan(), dir_ + "/no/such/dir/scan.scan"), std::runtime_error);
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

TEST_F(ScanFileTest, ReadsCommentsBlankLinesOptionalKeysAndRangesOnTheRangesLine) {
  const std::string path = Write("ok.scan",
                                 "# a scan\n"
                                 "\n"
                                 "scanloc_scan 1   # format 1\n"
                                 "beams 3\n"
                                 "angle_min_rad -0.5\n"
                                 "angle_increment_rad 0.5\n"
                                 "ranges 1.5 # two on this line\n"
                                 "  nan\n"
                                 "-1\n");
  const LaserScan scan = ReadScanFile(path);
  EXPECT_EQ(scan.layout.beam_count, 3u);
  EXPECT_DOUBLE_EQ(scan.layout.angle_min_rad, -0.5);
  EXPECT_DOUBLE_EQ(scan.layout.angle_increment_rad, 0.5);
  EXPECT_DOUBLE_EQ(scan.layout.range_min_m, 0.0);   // default
  EXPECT_DOUBLE_EQ(scan.layout.range_max_m, 20.0);  // default
  EXPECT_DOUBLE_EQ(scan.timestamp_s, 0.0);          // default
  ASSERT_EQ(scan.size(), 3u);
  EXPECT_DOUBLE_EQ(scan.ranges_m[0], 1.5);
  EXPECT_TRUE(std::isnan(scan.ranges_m[1]));
  EXPECT_DOUBLE_EQ(scan.ranges_m[2], -1.0);
  EXPECT_EQ(scan.CountValid(), 1u);
}

TEST_F(ScanFileTest, MissingHeaderIsAParseErrorAtTheFirstContentLine) {
  ExpectParseError("# comment\nbeams 3\n", 2, "scanloc_scan 1");
}

TEST_F(ScanFileTest, WrongVersionIsAParseError) {
  ExpectParseError("scanloc_scan 2\n", 1, "scanloc_scan 1");
}

TEST_F(ScanFileTest, UnknownKeyIsAParseErrorNamingTheKey) {
  ExpectParseError(kHeader + "colour blue\n", 5, "unknown key 'colour'");
}

TEST_F(ScanFileTest, NonNumericRangeIsAParseErrorAtItsLine) {
  ExpectParseError(kHeader + "ranges\n1.0 2.0\nthree\n", 7, "got 'three'");
}

TEST_F(ScanFileTest, TooFewRangesBeforeTheFileEndsIsAParseErrorAtTheRangesLine) {
  ExpectParseError(kHeader + "ranges\n1.0 2.0\n", 5, "expected 3 ranges, file ended after 2");
}

TEST_F(ScanFileTest, TooManyRangesOnOneLineIsAParseError) {
  ExpectParseError(kHeader + "ranges\n1.0 2.0 3.0 4.0\n", 6, "more than 3 ranges");
}

// A fourth range on the line after three is reported as too many ranges, not as an unknown key.
TEST_F(ScanFileTest, TooManyRangesOnTheNextLineIsReportedAsTooManyRanges) {
  ExpectParseError(kHeader + "ranges\n1.0 2.0 3.0\n4.0\n", 7, "more than 3 ranges");
}

TEST_F(ScanFileTest, RangesBeforeBeamsIsAParseError) {
  ExpectParseError("scanloc_scan 1\nranges 1 2 3\nbeams 3\n", 2, "'beams' must come before");
}

TEST_F(ScanFileTest, ZeroBeamsIsAParseError) {
  ExpectParseError("scanloc_scan 1\nbeams 0\n", 2, "beam count in [1, 100000]");
}

TEST_F(ScanFileTest, NegativeBeamsIsAParseError) {
  ExpectParseError("scanloc_scan 1\nbeams -4\n", 2, "beam count in [1, 100000]");
}

TEST_F(ScanFileTest, FractionalBeamsIsAParseError) {
  ExpectParseError("scanloc_scan 1\nbeams 2.5\n", 2, "beam count");
}

TEST_F(ScanFileTest, MissingAngleIncrementIsAParseErrorNamingTheRequiredKeys) {
  ExpectParseError("scanloc_scan 1\nbeams 3\nangle_min_rad 0\nranges 1 2 3\n", 4,
                   "'angle_increment_rad'");
}

TEST_F(ScanFileTest, NegativeAngleIncrementIsAParseError) {
  ExpectParseError("scanloc_scan 1\nbeams 3\nangle_increment_rad -0.1\n", 3, "positive step");
}

TEST_F(ScanFileTest, BeamsSpanningMoreThanOneRevolutionIsAParseError) {
  // 3 × 2.5 rad = 7.5 rad > 2π.
  ExpectParseError(
      "scanloc_scan 1\nbeams 3\nangle_min_rad 0\nangle_increment_rad 2.5\nranges 1 2 3\n", 5,
      "at most one revolution");
}

TEST_F(ScanFileTest, NaNInTheHeaderIsAParseError) {
  ExpectParseError("scanloc_scan 1\nbeams 3\nangle_min_rad nan\n", 3, "finite");
}

TEST_F(ScanFileTest, RangeMinAboveRangeMaxIsAParseError) {
  ExpectParseError(kHeader + "range_min_m 30\nranges 1 2 3\n", 6, "range_min_m < range_max_m");
}

TEST_F(ScanFileTest, EmptyFileIsAParseErrorNamingTheFileAndTheHeader) {
  const std::string path = Write("empty.scan", "");
  try {
    ReadScanFile(path);
    ADD_FAILURE() << "no ParseError for an empty file";
  } catch (const ParseError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
    EXPECT_NE(message.find("scanloc_scan 1"), std::string::npos) << message;
  }
}

TEST_F(ScanFileTest, UnreadablePathThrowsRuntimeErrorNamingIt) {
  const std::string path = dir_ + "/missing.scan";
  try {
    ReadScanFile(path);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const ParseError& error) {
    ADD_FAILURE() << "a missing file is not a parse error: " << error.what();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
}

TEST_F(ScanFileTest, LoadScanReadsTheNativeFormatForOtherSuffixes) {
  const std::string path = Write("s.scan", kHeader + "ranges 1 2 3\n");
  EXPECT_EQ(LoadScan(path).ranges_m, (std::vector<double>{1, 2, 3}));
}

TEST_F(ScanFileTest, LoadScanReadsTheIndexedFlaserMessageOfACarmenLog) {
  // FLASER n r1..rn  x y theta  odom_x odom_y odom_theta  ipc_timestamp host logger_timestamp
  const std::string path = Write("tiny.clf",
                                 "# tiny log\n"
                                 "ODOM 0 0 0 0 0 0 10.0 host 10.0\n"
                                 "FLASER 4 1.0 2.0 3.5 4.25 0 0 0 0 0 0 11.5 host 11.6\n"
                                 "FLASER 4 5.0 6.0 7.0 60.0 0 0 0 0 0 0 12.5 host 12.6\n");
  const LaserScan first = LoadScan(path);
  EXPECT_EQ(first.ranges_m, (std::vector<double>{1.0, 2.0, 3.5, 4.25}));
  EXPECT_EQ(first.layout.beam_count, 4u);
  // Even n: 180° from -90° in steps of π/n.
  EXPECT_NEAR(first.layout.angle_min_rad, -M_PI / 2.0, kAngleTolerance);
  EXPECT_NEAR(first.layout.angle_increment_rad, M_PI / 4.0, kAngleTolerance);
  EXPECT_DOUBLE_EQ(first.timestamp_s, 11.5);

  const LaserScan second = LoadScan(path, 1);
  EXPECT_EQ(second.ranges_m, (std::vector<double>{5.0, 6.0, 7.0, 60.0}));
  EXPECT_FALSE(second.IsValid(3)) << "60 m is beyond CARMEN's default 50 m maximum";
  EXPECT_DOUBLE_EQ(second.timestamp_s, 12.5);

  EXPECT_THROW(LoadScan(path, 2), std::runtime_error);
}

}  // namespace
}  // namespace scanloc
