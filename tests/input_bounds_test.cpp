// Bad input is answered with an error naming file and line, within memory that follows what a line
// can sensibly hold: over-long lines, scans beyond the beam cap, empty scans, absurd coordinates,
// files without a single scan; timestamps that go backwards are counted, not refused.

#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>
#include <sstream>
#include <string>

#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"
#include "scanloc/evaluation/relations_evaluation.hpp"
#include "scanloc/io/candidates_file.hpp"
#include "scanloc/io/carmen_log.hpp"
#include "scanloc/io/scan_file.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/io/trajectory.hpp"
#include "scanloc/maps/line_map.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

using testing::TemporaryDirTest;

// Expects `call` to throw ParseError at `line` whose message contains `part`.
template <class Call>
void ExpectParseError(Call call, std::size_t line, const std::string& part) {
  try {
    call();
    ADD_FAILURE() << "no ParseError (expected one containing '" << part << "')";
  } catch (const ParseError& error) {
    EXPECT_EQ(error.line(), line) << error.what();
    EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
  }
}

// A FLASER message of n beams at 1 m, odometry (x, y, 0), at time t.
std::string Flaser(std::size_t n, double x_m, double y_m, double t_s) {
  std::ostringstream line;
  line << "FLASER " << n;
  for (std::size_t i = 0; i < n; ++i) line << " 1.0";
  line << " 0 0 0 " << x_m << ' ' << y_m << " 0 " << t_s << " host " << t_s << '\n';
  return line.str();
}

// A sequence iteration with `beams` ranges at time t.
std::string SequenceLine(std::size_t beams, double t_s, const std::string& odometry = "[0, 0, 0]") {
  std::ostringstream line;
  line << "{\"timestamp_s\": " << t_s
       << ", \"scan\": {\"angle_min_rad\": -1.5, \"angle_increment_rad\": 0.01, \"ranges\": [";
  for (std::size_t i = 0; i < beams; ++i) line << (i ? ", " : "") << "1.0";
  line << "]}, \"odometry\": " << odometry << "}\n";
  return line.str();
}

const std::string kSequenceHeader = "{\"scanloc_sequence\": 1}\n";

TEST(BoundedLineTest, ReadsLinesAndALastLineWithoutNewline) {
  std::istringstream in("one\n\nthree");
  std::string line;
  ASSERT_TRUE(ReadBoundedLine(in, line, "f", 1, 8));
  EXPECT_EQ(line, "one");
  ASSERT_TRUE(ReadBoundedLine(in, line, "f", 2, 8));
  EXPECT_EQ(line, "");
  ASSERT_TRUE(ReadBoundedLine(in, line, "f", 3, 8));
  EXPECT_EQ(line, "three");
  EXPECT_FALSE(ReadBoundedLine(in, line, "f", 4, 8));
}

TEST(BoundedLineTest, RefusesALineLongerThanTheBoundNamingFileAndLine) {
  std::istringstream in("short\n123456789\n");
  std::string line;
  ASSERT_TRUE(ReadBoundedLine(in, line, "data.txt", 1, 8));
  ExpectParseError([&] { ReadBoundedLine(in, line, "data.txt", 2, 8); }, 2, "longer than 8 bytes");
  EXPECT_LE(line.size(), 8u) << "no more than the bound is kept";
}

TEST(SplitFieldsTest, StopsOneFieldPastTheLimit) {
  EXPECT_EQ(SplitFields("a b c d e f", 2).size(), 3u);
  EXPECT_EQ(SplitFields("  a\tb  # c d", 5), (std::vector<std::string>{"a", "b"}));
}

// The reader's overload reuses the strings of the line before: what they held must not leak into
// the next line's fields, whether it has more fields, fewer, or none.
TEST(SplitFieldsTest, ReusedFieldsHoldOnlyTheNewLine) {
  std::vector<std::string> fields;
  SplitFields("FLASER 3 a-rather-long-field-on-the-heap 2.5\r\n", 10, fields);
  EXPECT_EQ(fields,
            (std::vector<std::string>{"FLASER", "3", "a-rather-long-field-on-the-heap", "2.5"}));
  SplitFields("\tODOM 1\v2 3 4 5 6 7", 10, fields);
  EXPECT_EQ(fields, (std::vector<std::string>{"ODOM", "1", "2", "3", "4", "5", "6", "7"}));
  SplitFields("x # the rest is a comment", 10, fields);
  EXPECT_EQ(fields, std::vector<std::string>{"x"});
  SplitFields(" \f # only a comment", 10, fields);
  EXPECT_TRUE(fields.empty());
  SplitFields("a b c d e f", 2, fields);
  EXPECT_EQ(fields, (std::vector<std::string>{"a", "b", "c"}));
}

// Every text reader refuses a line over kMaxLineBytes (here a 17 MiB line of digits without
// newline, the 1 GB no-newline file in small) with the file and line.
class OverlongLineTest : public TemporaryDirTest {
 protected:
  std::string WriteOverlong(const std::string& name, const std::string& before) {
    return Write(name, before + std::string(kMaxLineBytes + (1 << 20), '7'));
  }
};

TEST_F(OverlongLineTest, EveryTextReaderRefusesIt) {
  ExpectParseError([&] { ReadLineMap(WriteOverlong("m.lines", "0 0 1 1\n")); }, 2, "longer than");
  ExpectParseError([&] { ReadCandidatesFile(WriteOverlong("c.txt", "")); }, 1, "longer than");
  ExpectParseError([&] { ReadScanFile(WriteOverlong("s.scan", "scanloc_scan 1\n")); }, 2,
                   "longer than");
  ExpectParseError([&] { ReadTumTrajectory(WriteOverlong("t.tum", "# t\n")); }, 2, "longer than");
  ExpectParseError([&] { ReadCorrectedPoses(WriteOverlong("p.txt", "")); }, 1, "longer than");
  ExpectParseError([&] { ReadRelations(WriteOverlong("r.relations", "")); }, 1, "longer than");
  ExpectParseError([&] { SequenceFileSource source(WriteOverlong("h.seq.jsonl", "")); }, 1,
                   "longer than");
  const std::string sequence = WriteOverlong("s.seq.jsonl", kSequenceHeader);
  ExpectParseError(
      [&] {
        SequenceFileSource source(sequence);
        Iteration iteration;
        source.Next(iteration);
      },
      2, "longer than");
  const std::string log = WriteOverlong("l.clf", Flaser(4, 0, 0, 1.0));
  ExpectParseError(
      [&] {
        CarmenReader reader(log);
        CarmenRecord record;
        while (reader.Next(record)) {
        }
      },
      2, "longer than");
}

TEST_F(OverlongLineTest, CarmenGzipReaderRefusesItAndResumesAfterIt) {
  const std::string path = dir_ + "/long.clf.gz";
  gzFile file = gzopen(path.c_str(), "wb");
  const std::string text =
      Flaser(4, 0, 0, 1.0) + std::string(kMaxLineBytes + 1000, '7') + "\n" + Flaser(4, 0, 0, 2.0);
  gzwrite(file, text.data(), static_cast<unsigned>(text.size()));
  gzclose(file);
  CarmenReader reader(path);
  CarmenRecord record;
  ASSERT_TRUE(reader.Next(record));
  ExpectParseError([&] { reader.Next(record); }, 2, "longer than");
  ASSERT_TRUE(reader.Next(record)) << "the reader continues after the long line";
  EXPECT_EQ(record.line, 3u);
  EXPECT_DOUBLE_EQ(record.timestamp_s, 2.0);
}

class BeamCapTest : public TemporaryDirTest {};

TEST_F(BeamCapTest, ScanFileRefusesABeamCountAboveTheCap) {
  const std::string path = Write("big.scan", "scanloc_scan 1\nbeams 100001\n");
  ExpectParseError([&] { ReadScanFile(path); }, 2, "beam count in [1, 100000]");
}

TEST_F(BeamCapTest, CarmenReaderRefusesAFlaserAboveTheCapBeforeSplittingIt) {
  const std::string path = Write("big.clf", Flaser(kMaxBeamsPerScan + 1, 0, 0, 1.0));
  CarmenReader reader(path);
  CarmenRecord record;
  ExpectParseError([&] { reader.Next(record); }, 1, "kMaxBeamsPerScan");
}

TEST_F(BeamCapTest, CarmenReaderAcceptsAScanAtTheCap) {
  CarmenReader reader(Write("cap.clf", Flaser(kMaxBeamsPerScan, 0, 0, 1.0)));
  CarmenRecord record;
  ASSERT_TRUE(reader.Next(record));
  EXPECT_EQ(record.scan.size(), kMaxBeamsPerScan);
}

TEST_F(BeamCapTest, SequenceRefusesAScanAboveTheCap) {
  SequenceFileSource source(Write("big.seq.jsonl", kSequenceHeader + SequenceLine(100001, 1.0)));
  Iteration iteration;
  ExpectParseError([&] { source.Next(iteration); }, 2, "100000");
}

class EmptyScanTest : public TemporaryDirTest {};

TEST_F(EmptyScanTest, SequenceAndScanFileBothRefuseAZeroBeamScan) {
  SequenceFileSource source(Write("zero.seq.jsonl", kSequenceHeader + SequenceLine(0, 1.0)));
  Iteration iteration;
  ExpectParseError([&] { source.Next(iteration); }, 2, "at least one beam");
  const std::string scan = Write("zero.scan", "scanloc_scan 1\nbeams 0\n");
  ExpectParseError([&] { ReadScanFile(scan); }, 2, "beam count in [1,");
}

class NoScanTest : public TemporaryDirTest {};

TEST_F(NoScanTest, CarmenSourceWithoutALaserMessageIsAnError) {
  for (const std::string& content :
       {std::string(), std::string("garbage that is no message\nmore garbage\n"),
        std::string(4096, '\0')}) {
    CarmenIterationSource source(Write("empty.clf", content));
    Iteration iteration;
    try {
      source.Next(iteration);
      ADD_FAILURE() << "no error for a log without scans";
    } catch (const ParseError& error) {
      EXPECT_NE(std::string(error.what()).find("no scan in"), std::string::npos) << error.what();
    }
  }
}

TEST_F(NoScanTest, SequenceWithAHeaderOnlyIsAnError) {
  SequenceFileSource source(Write("header.seq.jsonl", kSequenceHeader + "\n"));
  Iteration iteration;
  ExpectParseError([&] { source.Next(iteration); }, 2, "no scan in");
}

TEST_F(NoScanTest, SourcesWithScansEndWithoutError) {
  CarmenIterationSource carmen(Write("one.clf", Flaser(4, 0, 0, 1.0)));
  Iteration iteration;
  EXPECT_TRUE(carmen.Next(iteration));
  EXPECT_FALSE(carmen.Next(iteration));
  SequenceFileSource sequence(Write("one.seq.jsonl", kSequenceHeader + SequenceLine(3, 1.0)));
  EXPECT_TRUE(sequence.Next(iteration));
  EXPECT_FALSE(sequence.Next(iteration));
}

class CoordinateBoundTest : public TemporaryDirTest {};

TEST_F(CoordinateBoundTest, CarmenOdometryBeyondAMillionMetresIsRefused) {
  CarmenReader reader(Write("far.clf", Flaser(4, 0, 0, 1.0) + Flaser(4, 1e300, 0, 2.0)));
  CarmenRecord record;
  ASSERT_TRUE(reader.Next(record));
  ExpectParseError([&] { reader.Next(record); }, 2, "odometry beyond");
}

TEST_F(CoordinateBoundTest, SequenceOdometryBeyondAMillionMetresIsRefused) {
  SequenceFileSource source(
      Write("far.seq.jsonl", kSequenceHeader + SequenceLine(3, 1.0, "[1e300, 0, 0]")));
  Iteration iteration;
  ExpectParseError([&] { source.Next(iteration); }, 2, "odometry");
}

class TimestampOrderTest : public TemporaryDirTest {};

TEST_F(TimestampOrderTest, SourcesCountBackwardAndRepeatedTimestampsAndKeepGoing) {
  const std::string log =
      Write("back.clf", Flaser(4, 0, 0, 1.0) + Flaser(4, 0, 0, 3.0) + Flaser(4, 0, 0, 2.0) +
                            Flaser(4, 0, 0, 2.0) + Flaser(4, 0, 0, 4.0));
  CarmenIterationSource carmen(log);
  Iteration iteration;
  std::size_t scans = 0;
  while (carmen.Next(iteration)) ++scans;
  EXPECT_EQ(scans, 5u);
  EXPECT_EQ(carmen.timestamp_warnings(), 2u) << "3 -> 2 backwards, 2 -> 2 repeated";

  SequenceFileSource sequence(
      Write("back.seq.jsonl",
            kSequenceHeader + SequenceLine(3, 2.0) + SequenceLine(3, 1.0) + SequenceLine(3, 5.0)));
  scans = 0;
  while (sequence.Next(iteration)) ++scans;
  EXPECT_EQ(scans, 3u);
  EXPECT_EQ(sequence.timestamp_warnings(), 1u);
}

TEST(TimestampOrderCountTest, CountsPosesNotAfterTheirPredecessor) {
  std::vector<StampedPose> poses(5);
  const double times[] = {1.0, 2.0, 2.0, 1.5, 3.0};
  for (int i = 0; i < 5; ++i) poses[i].timestamp_s = times[i];
  EXPECT_EQ(CountNonIncreasingTimestamps(poses), 2u);
}

}  // namespace
}  // namespace scanloc
