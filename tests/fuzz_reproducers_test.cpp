// The inputs the fuzzers found (fuzz/crashes/, docs/FUZZING.md), replayed through the readers in
// the ordinary build: each is refused with a documented error, or read to a sane result.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scanloc/common/parse_error.hpp"
#include "scanloc/config/config.hpp"
#include "scanloc/io/carmen_log.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/io/trajectory.hpp"
#include "scanloc/maps/point_map_io.hpp"
#include "scanloc/report/run_records.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

const std::string kCrashes = std::string(SCANLOC_SOURCE_DIR) + "/fuzz/crashes/";

using testing::Contains;

// C1: a ParseError on a corrupt gzip stream ends the stream; resuming reaches the end.
TEST(FuzzReproducers, ACorruptGzipLogEndsAfterItsFirstErrorInsteadOfRepeatingIt) {
  for (const char* name :
       {"corrupt-gzip-parse-error-repeats", "truncated-gzip-parse-error-repeats.clf.gz"}) {
    SCOPED_TRACE(name);
    CarmenReader reader(kCrashes + "carmen_log/" + name);
    CarmenRecord record;
    int errors = 0, calls = 0;
    for (; calls < 1000; ++calls) {
      try {
        if (!reader.Next(record)) break;
      } catch (const ParseError&) {
        ++errors;
      }
    }
    EXPECT_LT(calls, 1000) << "the reader never reached the end";
    EXPECT_LE(errors, 1);
  }
}

// C2: 1e400 in a config file is refused naming the file.
TEST(FuzzReproducers, AnOverflowingNumberInAConfigIsRefusedNamingTheFile) {
  const std::string path = kCrashes + "config/number-overflow-escapes-as-json-out-of-range";
  try {
    LoadConfig(path);
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(Contains(e.what(), path)) << e.what();
  }
}

// C3, C4: a sequence header whose version is 3e40 or an array is a ParseError.
TEST(FuzzReproducers, ASequenceHeaderWithANonIntegerVersionIsAParseError) {
  for (const char* name : {"float-to-int-overflow", "header-version-array-escapes-as-type-error"}) {
    SCOPED_TRACE(name);
    EXPECT_THROW(
        {
          SequenceFileSource source(kCrashes + "native_sequence/" + name);
          Iteration iteration;
          while (source.Next(iteration)) {
          }
        },
        ParseError);
  }
}

// C5, C6, C7: PCDs with huge coordinates, a header announcing gigabytes, a COUNT that wraps;
// C9: headers PCL reads otherwise than scanloc's check (a repeated COUNT, a statement after DATA).
TEST(FuzzReproducers, AbsurdPcdsAreRefusedWithARuntimeError) {
  for (const char* name : {"huge-coordinate-cell-key-overflow", "header-makes-pcl-allocate-3.5-GB",
                           "hand-made-field-count-wraps-point-step.pcd",
                           "hand-made-repeated-count-makes-pcl-allocate-2.6-GB.pcd",
                           "hand-made-statement-after-data.pcd"}) {
    SCOPED_TRACE(name);
    EXPECT_THROW(LoadPointMapPcd(kCrashes + "pcd/" + name), std::runtime_error);
  }
}

// C8: quaternion components of 1e200 are normalised before the heading: finite, never NaN.
TEST(FuzzReproducers, AHugeQuaternionGivesAFiniteHeading) {
  const std::vector<StampedPose> poses =
      ReadTumTrajectory(kCrashes + "tum_trajectory/hand-made-huge-quaternion-nan-yaw.tum");
  ASSERT_FALSE(poses.empty());
  for (const StampedPose& pose : poses) EXPECT_TRUE(std::isfinite(pose.pose.yaw_rad));
}

// C11: a record whose map_points is 3.8e72 was cast to size_t (undefined); now refused with the
// field, the file and the line.
TEST(FuzzReproducers, ARecordCountBeyondItsTypeIsAParseErrorNamingTheField) {
  const std::string path = kCrashes + "run_records/map-points-beyond-size-t-casts-undefined";
  try {
    ReadIterationRows(path);
    FAIL() << "the record was read";
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("map_points: expected a whole number"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace scanloc
