// The likelihood field: its finest level is the largest Gaussian of the points within 3 σ, and
// every coarser level h holds the maximum of the finest over the 2^h × 2^h block starting at each
// cell (0 beyond the grid): the bound a branch and bound search relies on being exact.

#include "scanloc/maps/likelihood_field.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace scanloc {
namespace {

// Points scattered over the box and a little beyond it, with a fixed seed.
std::vector<Eigen::Vector2d> ScatteredPoints(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> x(-0.3, 2.3), y(-0.2, 1.6);
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < count; ++i) points.emplace_back(x(random), y(random));
  return points;
}

TEST(LikelihoodField, TheFinestLevelIsTheLargestGaussianOfThePointsWithinThreeSigma) {
  LikelihoodFieldOptions options;
  options.resolution_m = 0.05;
  options.sigma_m = 0.1;
  const std::vector<Eigen::Vector2d> points = ScatteredPoints(40, 3);
  const Eigen::Vector2d min_world(0.0, 0.0);
  const LikelihoodField field(points, min_world, {2.0, 1.3}, options);
  ASSERT_GE(field.width(), 41);
  ASSERT_GE(field.height(), 27);
  const int reach = static_cast<int>(std::ceil(3.0 * options.sigma_m / options.resolution_m));
  for (int iy = 0; iy < field.height(); ++iy)
    for (int ix = 0; ix < field.width(); ++ix) {
      const Eigen::Vector2d centre = min_world + 0.05 * Eigen::Vector2d(ix + 0.5, iy + 0.5);
      double expected = 0.0;
      for (const Eigen::Vector2d& p : points) {
        const Eigen::Vector2i cell = field.Cell(p);
        if (std::abs(cell.x() - ix) > reach || std::abs(cell.y() - iy) > reach) continue;
        expected = std::max(expected, std::exp(-(centre - p).squaredNorm() / (2.0 * 0.01)));
      }
      // Held to the nearest 255th.
      EXPECT_NEAR(field.At(0, ix, iy), expected, 0.5 / 255.0 + 1e-6) << ix << ", " << iy;
    }
}

TEST(LikelihoodField, EachCoarserLevelIsTheExactMaximumOfTheFinestOverItsBlock) {
  LikelihoodFieldOptions options;
  options.resolution_m = 0.05;
  options.levels = 6;
  const LikelihoodField field(ScatteredPoints(60, 7), {0.0, 0.0}, {2.0, 1.3}, options);
  ASSERT_EQ(field.levels(), 6);
  std::size_t nonzero = 0;
  for (int level = 1; level < field.levels(); ++level) {
    const int block = 1 << level;
    // The grid and one block beyond it on each side, where the block overlaps the grid partly.
    for (int iy = -block; iy < field.height() + block; ++iy)
      for (int ix = -block; ix < field.width() + block; ++ix) {
        float expected = 0.0f;
        for (int dy = 0; dy < block; ++dy)
          for (int dx = 0; dx < block; ++dx)
            expected = std::max(expected, field.At(0, ix + dx, iy + dy));
        const bool inside = ix >= 0 && iy >= 0 && ix < field.width() && iy < field.height();
        ASSERT_EQ(field.At(level, ix, iy), inside ? expected : 0.0f)
            << "level " << level << " cell " << ix << ", " << iy;
        nonzero += inside && expected > 0.0f;
      }
  }
  EXPECT_GT(nonzero, 1000u);  // the points cover the grid: the comparison is not of zeros
}

TEST(LikelihoodField, RebuiltInTheStorageOfAnotherFieldItEqualsOneBuiltAfresh) {
  LikelihoodFieldOptions coarse;
  coarse.resolution_m = 0.1;
  coarse.levels = 7;
  LikelihoodField reused(ScatteredPoints(80, 5), {-1.0, -1.0}, {3.0, 2.5}, coarse);
  LikelihoodFieldOptions fine;
  fine.levels = 4;
  const std::vector<Eigen::Vector2d> points = ScatteredPoints(30, 9);
  reused.Rebuild(points, {0.2, 0.1}, {1.9, 1.2}, fine);
  const LikelihoodField fresh(points, {0.2, 0.1}, {1.9, 1.2}, fine);
  ASSERT_EQ(reused.levels(), 4);
  ASSERT_EQ(reused.width(), fresh.width());
  ASSERT_EQ(reused.height(), fresh.height());
  EXPECT_EQ(reused.Cell({1.0, 1.0}), fresh.Cell({1.0, 1.0}));
  for (int level = 0; level < fresh.levels(); ++level)
    for (int iy = 0; iy < fresh.height(); ++iy)
      for (int ix = 0; ix < fresh.width(); ++ix)
        ASSERT_EQ(reused.At(level, ix, iy), fresh.At(level, ix, iy)) << level << " " << ix;
  // A box that cannot be built leaves the field as it was.
  EXPECT_THROW(reused.Rebuild(points, {1.0, 1.0}, {0.0, 0.0}, fine), std::invalid_argument);
  EXPECT_EQ(reused.width(), fresh.width());
}

// `count` random cells inside, on the edges and up to 8 cells beyond the grid on every side.
std::vector<Eigen::Vector2i> CellsInAndAround(const LikelihoodField& field, int count,
                                              unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> x(-8, field.width() + 8), y(-8, field.height() + 8);
  std::vector<Eigen::Vector2i> cells;
  for (int i = 0; i < count; ++i) cells.emplace_back(x(random), y(random));
  return cells;
}

TEST(LikelihoodField, ASumOverMovedCellsEqualsTheirValuesAddedOutsideCellsAddingZero) {
  const LikelihoodField field(ScatteredPoints(60, 7), {0.0, 0.0}, {2.0, 1.3});
  const std::vector<Eigen::Vector2i> cells = CellsInAndAround(field, 200, 5);
  std::size_t outside = 0;
  for (int level = 0; level < field.levels(); ++level)
    for (const auto& [dx, dy] : {std::pair{0, 0}, std::pair{-5, 3}, std::pair{7, -9}}) {
      double expected = 0.0;
      for (const Eigen::Vector2i& c : cells) {
        expected += field.At(level, c.x() + dx, c.y() + dy);
        outside += c.x() + dx < 0 || c.y() + dy >= field.height();
      }
      // Exact in quanta: only the float's rounding of the total (of at most 200) is left.
      EXPECT_NEAR(field.Sum(level, cells, dx, dy), expected, 2e-5)
          << level << " " << dx << " " << dy;
      EXPECT_GT(expected, 1.0);
    }
  EXPECT_GT(outside, 0u);
}

TEST(LikelihoodField, SplitCellsSumToTheSameQuantaAsCellsReadOneByOneAtEveryMoveWithinTheirReach) {
  const LikelihoodField field(ScatteredPoints(60, 7), {0.0, 0.0}, {2.0, 1.3});
  // Cells deep inside, near every edge and beyond the grid, so that both lists are used.
  const std::vector<Eigen::Vector2i> cells = CellsInAndAround(field, 300, 11);
  const int reach = 4;
  const LikelihoodField::MovedCells split = field.Split(cells, reach);
  EXPECT_EQ(split.size(), cells.size());
  EXPECT_GT(split.inside.size(), 50u);
  EXPECT_GT(split.edge.size(), 50u);
  for (int level = 0; level < field.levels(); ++level)
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx)
        ASSERT_EQ(
            static_cast<float>(field.SumQuanta(level, split, dx, dy)) * LikelihoodField::kQuantum,
            field.Sum(level, cells, dx, dy))
            << level << " " << dx << " " << dy;
  EXPECT_THROW(field.SumQuanta(0, split, reach + 1, 0), std::out_of_range);
  EXPECT_THROW(field.SumQuanta(0, split, 0, -reach - 1), std::out_of_range);
}

TEST(LikelihoodField, FourMovesSummedInOnePassGiveEachMovesOwnSumWhereverTheyLieWithinReach) {
  const LikelihoodField field(ScatteredPoints(60, 7), {0.0, 0.0}, {2.0, 1.3});
  const std::vector<Eigen::Vector2i> cells = CellsInAndAround(field, 300, 11);
  const int reach = 6;
  const LikelihoodField::MovedCells split = field.Split(cells, reach);
  for (int level = 0; level < field.levels(); ++level)
    for (const int step : {0, 1, 2, 4})
      for (int dy = -reach; dy + step <= reach; ++dy)
        for (int dx = -reach; dx + step <= reach; ++dx) {
          const std::array<unsigned, 4> four = field.SumQuantaOfFour(level, split, dx, dy, step);
          ASSERT_EQ(four[0], field.SumQuanta(level, split, dx, dy));
          ASSERT_EQ(four[1], field.SumQuanta(level, split, dx + step, dy));
          ASSERT_EQ(four[2], field.SumQuanta(level, split, dx, dy + step));
          ASSERT_EQ(four[3], field.SumQuanta(level, split, dx + step, dy + step))
              << level << " " << dx << " " << dy << " " << step;
        }
  EXPECT_THROW(field.SumQuantaOfFour(0, split, reach - 1, 0, 2), std::out_of_range);
  EXPECT_THROW(field.SumQuantaOfFour(0, split, 0, -reach - 1, 1), std::out_of_range);
  EXPECT_THROW(field.SumQuantaOfFour(0, split, 0, 0, -1), std::out_of_range);
}

}  // namespace
}  // namespace scanloc
