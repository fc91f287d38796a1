// ExtendMap: carving, then insertion (3.6); with carving off it is the insertion alone.

#include "scanloc/session/map_extension.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace scanloc {
namespace {

TEST(MapExtension, APointSeenThroughIsCarvedBeforeTheScanIsInserted) {
  const LineMap room = testing::RectangleRoom(8.0, 6.0);
  const Pose2D T_world_laser{4.0, 3.0, 0.0};
  const LaserScan scan = testing::NoisyScan(room, T_world_laser, 720, 0.0, 1);
  PointMap map;
  // A stray point 1 m in front of the laser, where every scan sees through to the wall.
  map.Insert(Eigen::Vector2d(5.0, 3.0), 0.05);
  map.Insert(Eigen::Vector2d(5.0, 3.0), 0.05);  // seen twice: must be seen through more
  const std::size_t before = map.live_size();
  std::size_t carved = 0;
  for (int pass = 0; pass < 3; ++pass) carved += ExtendMap(map, scan, T_world_laser, {});
  EXPECT_GE(carved, 1u);
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map.alive(i)) {
      EXPECT_GT((map.point(i) - Eigen::Vector2d(5.0, 3.0)).norm(), 0.5);
    }
  EXPECT_GT(map.live_size(), before);  // the room's walls went in
}

TEST(MapExtension, WithCarvingOffItIsTheInsertionAlone) {
  const LineMap room = testing::RectangleRoom(8.0, 6.0);
  const Pose2D T_world_laser{4.0, 3.0, 0.0};
  const LaserScan scan = testing::NoisyScan(room, T_world_laser, 720, 0.0, 1);
  PointMap extended, inserted;
  extended.Insert(Eigen::Vector2d(5.0, 3.0), 0.05);
  inserted.Insert(Eigen::Vector2d(5.0, 3.0), 0.05);
  MapExtensionOptions off;
  off.free_space_margin_m = 0.0;
  EXPECT_EQ(ExtendMap(extended, scan, T_world_laser, off), 0u);
  inserted.InsertScan(scan, T_world_laser);
  ASSERT_EQ(extended.size(), inserted.size());
  EXPECT_EQ(extended.live_size(), inserted.live_size());
  for (std::size_t i = 0; i < extended.size(); ++i)
    EXPECT_EQ(extended.point(i), inserted.point(i)) << i;
}

}  // namespace
}  // namespace scanloc
