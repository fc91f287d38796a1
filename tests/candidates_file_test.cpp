#include "scanloc/io/candidates_file.hpp"

#include <gtest/gtest.h>

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

class CandidatesFileTest : public testing::TemporaryDirTest {
 protected:
  using TemporaryDirTest::Write;
  std::string Write(const std::string& content) const { return Write("candidates.txt", content); }

  // Reading `content` fails with a ParseError at `line` naming file, line and `expected`.
  void ExpectParseError(const std::string& content, std::size_t line,
                        const std::string& expected) const {
    const std::string path = Write(content);
    SCOPED_TRACE(content);
    testing::ExpectParseError([&] { ReadCandidatesFile(path); }, path, line, expected);
  }
};

void ExpectCandidate(const Candidate& c, double x_m, double y_m, double yaw_rad,
                     const std::string& label) {
  EXPECT_DOUBLE_EQ(c.T_world_robot.x_m, x_m) << label;
  EXPECT_DOUBLE_EQ(c.T_world_robot.y_m, y_m) << label;
  EXPECT_DOUBLE_EQ(c.T_world_robot.yaw_rad, yaw_rad) << label;
  EXPECT_EQ(c.label, label);
}

TEST_F(CandidatesFileTest, ReadsPosturesWithTheirLabels) {
  const auto candidates =
      ReadCandidatesFile(Write("1.102 3.111 0.046 p0\n4.252 3.868 -3.084 far\n"));
  ASSERT_EQ(candidates.size(), 2u);
  ExpectCandidate(candidates[0], 1.102, 3.111, 0.046, "p0");
  ExpectCandidate(candidates[1], 4.252, 3.868, -3.084, "far");
}

TEST_F(CandidatesFileTest, MissingLabelsDefaultToPIndexCountingOnlyCandidates) {
  const auto candidates =
      ReadCandidatesFile(Write("# header comment\n\n1 2 0.5\n   \n3 4 -0.5  # trailing comment\n"
                               "5 6 0 named\n7 8 1\n"));
  ASSERT_EQ(candidates.size(), 4u);
  ExpectCandidate(candidates[0], 1, 2, 0.5, "p0");
  ExpectCandidate(candidates[1], 3, 4, -0.5, "p1");
  ExpectCandidate(candidates[2], 5, 6, 0, "named");
  ExpectCandidate(candidates[3], 7, 8, 1, "p3");
}

TEST_F(CandidatesFileTest, FileOfCommentsAndBlankLinesGivesNoCandidate) {
  EXPECT_TRUE(ReadCandidatesFile(Write("# nothing\n\n  # still nothing\n")).empty());
}

TEST_F(CandidatesFileTest, TwoFieldsIsAParseErrorAtItsLine) {
  ExpectParseError("1 2 3\n# comment\n1 2\n", 3, "expected 'x y theta [label]'");
}

TEST_F(CandidatesFileTest, FiveFieldsIsAParseErrorAtItsLine) {
  ExpectParseError("1 2 3 a b\n", 1, "got 5 fields");
}

TEST_F(CandidatesFileTest, NonNumericCoordinateIsAParseErrorNamingTheField) {
  ExpectParseError("\n1 two 3\n", 2, "y in metres, got 'two'");
}

TEST_F(CandidatesFileTest, NonFiniteAngleIsAParseError) {
  ExpectParseError("1 2 nan p0\n", 1, "theta in radians");
  ExpectParseError("1 2 inf p0\n", 1, "theta in radians");
}

TEST_F(CandidatesFileTest, NumberWithTrailingGarbageIsAParseError) {
  ExpectParseError("1.5m 2 3\n", 1, "x in metres, got '1.5m'");
}

TEST_F(CandidatesFileTest, MissingFileThrowsRuntimeErrorNamingIt) {
  const std::string path = dir_ + "/missing.txt";
  try {
    ReadCandidatesFile(path);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
}

TEST_F(CandidatesFileTest, RoundTripKeepsPosturesAndLabels) {
  const std::vector<Candidate> candidates = {{{1.102, 3.111, 0.046}, "p0"},
                                             {{-4.252, 3.868, -3.084}, "p1"},
                                             {{0.0, 1e-3, 3.14159}, "mirror"}};
  const std::string path = dir_ + "/out.txt";
  WriteCandidatesFile(candidates, path);
  const auto read = ReadCandidatesFile(path);
  ASSERT_EQ(read.size(), candidates.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    const Pose2D& p = candidates[i].T_world_robot;
    ExpectCandidate(read[i], p.x_m, p.y_m, p.yaw_rad, candidates[i].label);
  }
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir_))
    names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"out.txt"}) << "no temporary file remains";
}

TEST_F(CandidatesFileTest, RoundTripKeepsPosturesToTenSignificantDigits) {
  const std::vector<Candidate> candidates = {{{1.0 / 3.0, -2.0 / 7.0, M_PI / 7.0}, "thirds"}};
  const std::string path = dir_ + "/out.txt";
  WriteCandidatesFile(candidates, path);
  const auto read = ReadCandidatesFile(path);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_NEAR(read[0].T_world_robot.x_m, 1.0 / 3.0, 1e-10);
  EXPECT_NEAR(read[0].T_world_robot.y_m, -2.0 / 7.0, 1e-10);
  EXPECT_NEAR(read[0].T_world_robot.yaw_rad, M_PI / 7.0, 1e-10);
}

// The writer refuses what the reader could not read back as written: a label with a space or
// a '#', an empty label, a NaN coordinate.
TEST_F(CandidatesFileTest, WriterRefusesWhatTheReaderCannotReadBack) {
  const std::string path = dir_ + "/out.txt";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Candidate& bad : {Candidate{{1, 2, 3}, "two words"}, Candidate{{1, 2, 3}, "#x"},
                               Candidate{{1, 2, 3}, ""}, Candidate{{nan, 2, 3}, "p0"}}) {
    EXPECT_THROW(WriteCandidatesFile({bad}, path), std::invalid_argument) << bad.label;
    EXPECT_FALSE(std::filesystem::exists(path)) << bad.label;
  }
}

}  // namespace
}  // namespace scanloc
