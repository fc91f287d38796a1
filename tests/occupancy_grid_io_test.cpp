// WriteOccupancyGrid and ReadOccupancyGridImage: map_server's files written and read back.
#include "scanloc/io/occupancy_grid_io.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "run_scanloc.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

class OccupancyGridIoTest : public testing::TemporaryDirTest {
 protected:
  // A 3 × 2 grid: the bottom row occupied, free, unknown; the top row free.
  static OccupancyGrid Grid() {
    OccupancyGrid grid;
    grid.resolution_m = 0.1;
    grid.origin_m = {-1.5, 2.25};
    grid.width = 3;
    grid.height = 2;
    grid.log_odds = {3.0f, -3.0f, 0.0f, -3.0f, -3.0f, -3.0f};
    return grid;
  }
  std::string Message(const std::string& yaml_path) {
    try {
      ReadOccupancyGridImage(yaml_path);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(OccupancyGridIoTest, AWrittenGridReadsBackWithItsOriginResolutionAndPixelsTopRowFirst) {
  const OccupancyGridFiles files = WriteOccupancyGrid(dir_, Grid(), "room");
  EXPECT_EQ(files.yaml_path, OccupancyGridPaths(dir_, "room").yaml_path);
  const OccupancyGridImage image = ReadOccupancyGridImage(files.yaml_path);
  EXPECT_DOUBLE_EQ(image.resolution_m, 0.1);
  EXPECT_DOUBLE_EQ(image.origin_m.x(), -1.5);
  EXPECT_DOUBLE_EQ(image.origin_m.y(), 2.25);
  ASSERT_EQ(image.width, 3u);
  ASSERT_EQ(image.height, 2u);
  EXPECT_EQ(image.pixels, (std::vector<unsigned char>{kPgmFree, kPgmFree, kPgmFree, kPgmOccupied,
                                                      kPgmFree, kPgmUnknown}));
}

TEST_F(OccupancyGridIoTest, ATruncatedImageOrAMissingKeyIsAnErrorNamingTheFile) {
  const OccupancyGridFiles files = WriteOccupancyGrid(dir_, Grid());
  const std::string pgm = testing::ReadWholeFile(files.image_path);
  Write("map.pgm", pgm.substr(0, pgm.size() - 2));
  EXPECT_TRUE(testing::Contains(Message(files.yaml_path),
                                files.image_path + ": expected 6 pixels, the file ends before"));
  const std::string yaml = Write("bad.yaml", "image: map.pgm\nresolution: 0.05\n");
  EXPECT_EQ(Message(yaml), yaml + ": expected the key origin");
  const std::string negative =
      Write("neg.yaml", "image: map.pgm\nresolution: -1\norigin: [0, 0, 0]\n");
  EXPECT_TRUE(testing::Contains(Message(negative), "expected a positive resolution"));
}

}  // namespace
}  // namespace scanloc
