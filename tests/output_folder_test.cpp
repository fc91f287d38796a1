// RefuseNonEmptyFolder and RefuseToReplace: earlier results are not written over unless forced.
#include "scanloc/common/output_folder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "test_support.hpp"

namespace scanloc {
namespace {

class OutputFolderTest : public testing::TemporaryDirTest {};

std::string MessageOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST_F(OutputFolderTest, AnAbsentOrEmptyFolderIsAcceptedAndLeftAsItWas) {
  EXPECT_NO_THROW(RefuseNonEmptyFolder(dir_ + "/new/run", false));
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/new"));  // not created: the writer does that
  std::filesystem::create_directory(dir_ + "/empty");
  EXPECT_NO_THROW(RefuseNonEmptyFolder(dir_ + "/empty", false));
}

TEST_F(OutputFolderTest, AFolderWithAnythingInItIsRefusedNamingAnEntryAndForce) {
  Write("summary.json", "{}");
  const std::string message = MessageOf([&] { RefuseNonEmptyFolder(dir_, false); });
  EXPECT_TRUE(testing::Contains(message, dir_ + " already exists and is not empty (1 entry: "
                                                "summary.json); give --force"))
      << message;
  EXPECT_NO_THROW(RefuseNonEmptyFolder(dir_, true));
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/summary.json"));
}

TEST_F(OutputFolderTest, AFileInPlaceOfTheFolderIsRefusedEvenWhenForced) {
  const std::string file = Write("run", "not a folder");
  EXPECT_TRUE(testing::Contains(MessageOf([&] { RefuseNonEmptyFolder(file, true); }),
                                "exists and is not a folder"));
}

TEST_F(OutputFolderTest, ExistingFilesAreNotReplacedUnlessForced) {
  const std::string grid = Write("map.pgm", "P5");
  EXPECT_NO_THROW(RefuseToReplace({dir_ + "/other.pgm"}, false));
  EXPECT_EQ(MessageOf([&] {
              RefuseToReplace({dir_ + "/other.pgm", grid}, false);
            }),
            grid + " already exists; give --force to replace it");
  EXPECT_NO_THROW(RefuseToReplace({grid}, true));
}

}  // namespace
}  // namespace scanloc
