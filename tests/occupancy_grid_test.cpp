#include "scanloc/maps/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "test_support.hpp"

namespace scanloc {
namespace {

// One beam along +x from the centre of cell (0, 0): 1 m at 0.05 m cells ends in cell 20.
LaserScan OneBeam(double range_m) {
  LaserScan scan;
  scan.layout.beam_count = 1;
  scan.layout.angle_min_rad = 0.0;
  scan.layout.angle_increment_rad = 0.1;
  scan.ranges_m = {range_m};
  return scan;
}

TEST(OccupancyGrid, BeamMarksCrossedCellsMissedOnceAndItsEndCellHit) {
  OccupancyGridOptions options;
  options.margin_cells = 0;
  OccupancyGridBuilder builder(options);
  builder.AddScan(OneBeam(1.0), Pose2D(0.025, 0.025, 0.0));
  const OccupancyGrid grid = builder.Build();
  ASSERT_EQ(grid.width, 21u);
  ASSERT_EQ(grid.height, 1u);
  EXPECT_DOUBLE_EQ(grid.origin_m.x(), 0.0);
  for (std::size_t x = 0; x < 20; ++x) EXPECT_FLOAT_EQ(grid.LogOdds(x, 0), -0.2f) << "cell " << x;
  EXPECT_FLOAT_EQ(grid.LogOdds(20, 0), 0.85f);
  EXPECT_EQ(grid.State(20, 0), CellState::kOccupied);  // p = 0.70 > 0.65
  EXPECT_EQ(grid.State(3, 0), CellState::kUnknown);    // p = 0.45: one miss is not enough
}

TEST(OccupancyGrid, AScanMovedAfterTheFactIsCastFromItsNewPostureOnly) {
  OccupancyGridOptions options;
  options.margin_cells = 0;
  OccupancyGridBuilder moved(options), direct(options);
  moved.AddScan(OneBeam(1.0), Pose2D(0.025, 0.025, 0.0));
  moved.AddScan(OneBeam(0.5), Pose2D(0.025, 0.025, 0.0));
  moved.MoveScan(1, Pose2D(0.025, 0.525, M_PI / 2.0));  // the second beam now points up
  direct.AddScan(OneBeam(1.0), Pose2D(0.025, 0.025, 0.0));
  direct.AddScan(OneBeam(0.5), Pose2D(0.025, 0.525, M_PI / 2.0));
  const OccupancyGrid a = moved.Build(), b = direct.Build();
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  EXPECT_EQ(a.log_odds, b.log_odds);
  EXPECT_EQ(a.height, 21u);  // from y = 0 up to the moved beam's end at 1.025 m
  EXPECT_THROW(moved.MoveScan(2, Pose2D()), std::out_of_range);
}

TEST(OccupancyGrid, ACellOneBeamEndsInIsHitOnlyThoughAnotherBeamOfTheScanCrossesIt) {
  // Two beams a microradian apart along +x: one ends in cell 10, the other crosses it to cell 20.
  // Either beam order: cell 10 takes the hit alone, every other cell one vote.
  for (const bool short_first : {true, false}) {
    OccupancyGridOptions options;
    options.margin_cells = 0;
    OccupancyGridBuilder builder(options);
    LaserScan scan;
    scan.layout.beam_count = 2;
    scan.layout.angle_min_rad = 0.0;
    scan.layout.angle_increment_rad = 1e-6;
    scan.ranges_m = short_first ? std::vector<double>{0.5, 1.0} : std::vector<double>{1.0, 0.5};
    builder.AddScan(scan, Pose2D(0.025, 0.025, 0.0));
    const OccupancyGrid grid = builder.Build();
    ASSERT_EQ(grid.width, 21u) << short_first;
    for (std::size_t x = 0; x < 21; ++x)
      EXPECT_FLOAT_EQ(grid.LogOdds(x, 0), x == 10 || x == 20 ? 0.85f : -0.2f)
          << "cell " << x << (short_first ? ", short beam first" : ", long beam first");
  }
}

TEST(OccupancyGrid, RepeatedMissesMakeFreeCellsAndTheClampBoundsLogOdds) {
  OccupancyGridBuilder builder;
  for (int i = 0; i < 10; ++i) builder.AddScan(OneBeam(1.0), Pose2D(0.025, 0.025, 0.0));
  const OccupancyGrid grid = builder.Build();
  std::size_t x = 0, y = 0;
  ASSERT_TRUE(grid.CellOf({0.525, 0.025}, x, y));
  EXPECT_FLOAT_EQ(grid.LogOdds(x, y), -2.0f);  // 10 × −0.2
  EXPECT_EQ(grid.State(x, y), CellState::kFree);
  ASSERT_TRUE(grid.CellOf({1.025, 0.025}, x, y));
  EXPECT_FLOAT_EQ(grid.LogOdds(x, y), 3.5f);  // 10 × 0.85, clamped at 3.5
}

TEST(OccupancyGrid, BeamsWithoutEchoLeaveEveryCellUnknown) {
  OccupancyGridBuilder builder;
  builder.AddScan(OneBeam(-1.0), Pose2D(1.0, 1.0, 0.0));
  const OccupancyGrid grid = builder.Build();
  ASSERT_GT(grid.width * grid.height, 0u);
  for (float l : grid.log_odds) EXPECT_EQ(l, 0.0f);
  EXPECT_EQ(grid.Probability(0, 0), 0.5);
  EXPECT_EQ(grid.State(0, 0), CellState::kUnknown);
}

// The probability 1 − 1/(1 + e^l) on both sides of l = 0, where an unobserved cell's is exactly ½.
TEST(OccupancyGrid, ProbabilityIsTheLogisticOfTheLogOdds) {
  OccupancyGridBuilder builder;
  for (int i = 0; i < 10; ++i) builder.AddScan(OneBeam(1.0), Pose2D(0.025, 0.025, 0.0));
  const OccupancyGrid grid = builder.Build();
  for (std::size_t y = 0; y < grid.height; ++y)
    for (std::size_t x = 0; x < grid.width; ++x) {
      const double l = grid.LogOdds(x, y);
      EXPECT_NEAR(grid.Probability(x, y), 1.0 / (1.0 + std::exp(-l)), 1e-14) << x << ", " << y;
    }
  std::size_t x = 0, y = 0;
  ASSERT_TRUE(grid.CellOf({1.025, 0.025}, x, y));
  EXPECT_NEAR(grid.Probability(x, y), 1.0 / (1.0 + std::exp(-3.5)), 1e-7);
}

TEST(OccupancyGrid, RoomScansGiveWallsOccupiedAndTheInsideFree) {
  const LineMap room = testing::RectangleRoom(4.0, 3.0);
  OccupancyGridBuilder builder;
  // Eight scans: a cell crossed by all of them reaches 8 × −0.2, below free_thresh's −1.41 (eight
  // misses are needed).
  for (const Pose2D& pose : {Pose2D(1.0, 1.0, 0.0), Pose2D(2.0, 1.5, 0.3), Pose2D(3.0, 2.0, -0.2),
                             Pose2D(1.2, 2.2, 0.1), Pose2D(2.8, 0.8, 0.2), Pose2D(2.2, 1.2, 0.0),
                             Pose2D(1.8, 1.8, -0.1), Pose2D(2.5, 1.9, 0.4)})
    builder.AddScan(testing::NoisyScan(room, pose, 1440, 0.0, 1), pose);
  const OccupancyGrid grid = builder.Build();
  std::size_t x = 0, y = 0, walls = 0, occupied_walls = 0;
  for (const Eigen::Vector2d& p : SampleLineMap(room, 0.01)) {
    if (!grid.CellOf(p, x, y)) continue;
    ++walls;
    // The wall's cell, or its neighbour across the cell edge the wall lies on.
    bool occupied = false;
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        const long nx = static_cast<long>(x) + dx, ny = static_cast<long>(y) + dy;
        occupied = occupied || (nx >= 0 && ny >= 0 && nx < static_cast<long>(grid.width) &&
                                ny < static_cast<long>(grid.height) &&
                                grid.State(nx, ny) == CellState::kOccupied);
      }
    occupied_walls += occupied;
  }
  EXPECT_GT(walls, 1300u);
  EXPECT_GE(static_cast<double>(occupied_walls) / walls, 0.99) << occupied_walls << " of " << walls;
  ASSERT_TRUE(grid.CellOf({2.0, 1.5}, x, y));
  EXPECT_EQ(grid.State(x, y), CellState::kFree);
}

TEST(OccupancyGrid, OptionsOutsideTheirRangesAreRefused) {
  OccupancyGridOptions options;
  options.resolution_m = 0.0;
  EXPECT_THROW(OccupancyGridBuilder{options}, std::invalid_argument);
  options = {};
  options.log_odds_miss = 0.1;
  EXPECT_THROW(OccupancyGridBuilder{options}, std::invalid_argument);
  options = {};
  options.free_probability = 0.7;
  EXPECT_THROW(OccupancyGridBuilder{options}, std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
