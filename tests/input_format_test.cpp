#include "scanloc/io/input_format.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "scanloc/io/sequence_sources.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

const std::string kSource = SCANLOC_SOURCE_DIR;

class InputFormatTest : public testing::TemporaryDirTest {
 protected:
  std::string Copy(const std::string& from, const std::string& name) const {
    const std::string path = dir_ + "/" + name;
    std::filesystem::copy_file(kSource + "/" + from, path);
    return path;
  }
  std::string WriteGzip(const std::string& name, const std::string& content) const {
    const std::string path = dir_ + "/" + name;
    gzFile file = gzopen(path.c_str(), "wb");
    gzwrite(file, content.data(), static_cast<unsigned>(content.size()));
    gzclose(file);
    return path;
  }
  // The message DetectInputFormat throws for the file, or "" when it throws none.
  static std::string ErrorFor(const std::string& path) {
    try {
      DetectInputFormat(path);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
};

const char kCarmen[] =
    "# a comment\n"
    "PARAM robot_frontlaser_offset 0.1 host 0\n"
    "ODOM 0 0 0 0 0 0 1.0 host 1.0\n";

TEST_F(InputFormatTest, CarmenLogIsRecognisedWhateverItsName) {
  EXPECT_EQ(DetectInputFormat(Write("log.txt", kCarmen)), InputFormat::kCarmenLog);
  EXPECT_EQ(DetectInputFormat(WriteGzip("log.dat", kCarmen)), InputFormat::kCarmenLog);
  EXPECT_EQ(DetectInputFormat(Write("noext", "\n\nFLASER 2 1 1 0 0 0 0 0 0 1 h 1\n")),
            InputFormat::kCarmenLog);
}

TEST_F(InputFormatTest, RosBagIsRecognisedWhateverItsName) {
  EXPECT_EQ(DetectInputFormat(Copy("datasets/classroom/classroom.bag", "run.dat")),
            InputFormat::kRosBag);
}

TEST_F(InputFormatTest, SequenceIsRecognisedWhateverItsName) {
  EXPECT_EQ(DetectInputFormat(Copy("datasets/classroom/classroom.seq.jsonl", "run.clf")),
            InputFormat::kScanSequence);
}

TEST_F(InputFormatTest, UnknownContentIsAnErrorListingTheAcceptedFormats) {
  const std::string message = ErrorFor(Write("scan.csv", "x,y\n1,2\n"));
  EXPECT_NE(message.find("scan.csv"), std::string::npos) << message;
  for (const char* format : {"CARMEN log", "ROS 1 bag", "scanloc sequence"})
    EXPECT_NE(message.find(format), std::string::npos) << format << " in: " << message;
  EXPECT_NE(ErrorFor(Write("empty.clf", "")).find("empty file"), std::string::npos);
  EXPECT_NE(ErrorFor(dir_ + "/absent.clf").find("absent.clf"), std::string::npos);
}

TEST_F(InputFormatTest, OpenIterationSourceReadsACarmenLogNamedTxt) {
  const std::string path =
      Write("log.txt", std::string(kCarmen) + "FLASER 2 1.5 2.5 0 0 0 0.5 0.25 0.1 2.0 host 2.0\n");
  auto source = OpenIterationSource(path);
  ASSERT_NE(dynamic_cast<CarmenIterationSource*>(source.get()), nullptr);
  Iteration iteration;
  ASSERT_TRUE(source->Next(iteration));
  EXPECT_EQ(iteration.scan.size(), 2u);
  EXPECT_DOUBLE_EQ(iteration.odometry->x_m, 0.5);
  EXPECT_DOUBLE_EQ(source->mounting().T_robot_laser.x_m, 0.1);
}

}  // namespace
}  // namespace scanloc
