#include "scanloc/maps/line_map.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scanloc/common/parse_error.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

std::string WriteText(const std::string& dir, const std::string& name, const std::string& text) {
  return testing::WriteText(dir + "/" + name, text);
}

TEST(ReadLineMap, ParsesSegmentsCommentsAndBlankLines) {
  const auto dir = testing::TemporaryDir();
  const auto path = WriteText(dir, "room.lines", "# a room\n\n0 0 4 0  # south\n4 0 4 3\n");
  const LineMap map = ReadLineMap(path);
  ASSERT_EQ(map.segments.size(), 2u);
  EXPECT_DOUBLE_EQ(map.segments[1].b.y(), 3.0);
}

TEST(ReadLineMap, EmptyFileGivesEmptyMap) {
  const auto dir = testing::TemporaryDir();
  EXPECT_TRUE(ReadLineMap(WriteText(dir, "empty.lines", "")).empty());
}

TEST(ReadLineMap, WrongFieldCountNamesFileAndLine) {
  const auto dir = testing::TemporaryDir();
  const auto path = WriteText(dir, "bad.lines", "0 0 1 1\n\n0 0 1\n");
  try {
    ReadLineMap(path);
    FAIL() << "expected a ParseError";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), 3u);
    EXPECT_NE(std::string(e.what()).find("bad.lines:3:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("x1 y1 x2 y2"), std::string::npos) << e.what();
  }
}

TEST(ReadLineMap, NonNumericAndNonFiniteValuesAreRefused) {
  const auto dir = testing::TemporaryDir();
  EXPECT_THROW(ReadLineMap(WriteText(dir, "a.lines", "0 0 1 one\n")), ParseError);
  EXPECT_THROW(ReadLineMap(WriteText(dir, "b.lines", "0 nan 1 1\n")), ParseError);
  EXPECT_THROW(ReadLineMap(WriteText(dir, "c.lines", "0 0 inf 1\n")), ParseError);
  EXPECT_THROW(ReadLineMap(WriteText(dir, "d.lines", "0 0 1e999 1\n")), ParseError);
  EXPECT_THROW(ReadLineMap(dir + "/missing.lines"), std::runtime_error);
}

TEST(WriteLineMap, RoundTripsAndLeavesNoTemporaryFile) {
  const auto dir = testing::TemporaryDir();
  const LineMap room = testing::RectangleRoom(4.5, 3.25);
  WriteLineMap(room, dir + "/room.lines");
  const LineMap back = ReadLineMap(dir + "/room.lines");
  ASSERT_EQ(back.segments.size(), 4u);
  EXPECT_DOUBLE_EQ(back.segments[2].a.x(), 4.5);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
}

TEST(SampleLineMap, IncludesVerticesAndRespectsSpacing) {
  LineMap map;
  map.segments = {{{0, 0}, {1, 0}}, {{2, 2}, {2, 2}}};
  const auto points = SampleLineMap(map, 0.3);
  // 1 m at ≤ 0.3 m: 4 intervals, 5 points; the zero-length segment gives its single point.
  ASSERT_EQ(points.size(), 6u);
  EXPECT_DOUBLE_EQ(points.front().x(), 0.0);
  EXPECT_DOUBLE_EQ(points[4].x(), 1.0);
  EXPECT_NEAR(points[1].x(), 0.25, 1e-12);
  EXPECT_THROW(SampleLineMap(map, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
