// The point map's de-duplication tables against std::unordered_map: the hash table over random
// insertions and erasures packed into few home slots (so that probe runs wrap around the array and
// erasures must shift them back), and the tiles of cells over the same, negative cells and tile
// borders included, looked up one by one and nine at a time.
#include "maps/cell_table.hpp"
#include "maps/cell_tiles.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <unordered_map>
#include <utility>

namespace scanloc {
namespace {

// The point map's key of cell (x, y).
std::int64_t Key(std::int64_t x, std::int64_t y) {
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(x) << 32) ^
                                   (static_cast<std::uint64_t>(y) & 0xffffffffULL));
}

TEST(CellTable, AgreesWithUnorderedMapOverThirtyThousandRandomInsertionsAndErasures) {
  std::mt19937_64 rng(20261129);
  // Keys from a small range (cells of a few square metres, negative ones included), so that most
  // operations meet keys already held and runs collide.
  std::uniform_int_distribution<std::int64_t> coordinate(-40, 40);
  std::uniform_int_distribution<std::uint32_t> value(0, 1000);
  std::bernoulli_distribution erase(0.4);
  CellTable table;
  std::unordered_map<std::int64_t, std::uint32_t> reference;
  for (int step = 0; step < 30000; ++step) {
    const std::int64_t cell_x = coordinate(rng);
    const std::int64_t key = Key(cell_x, coordinate(rng));
    if (erase(rng)) {
      // Erased only when it holds the value asked for; half the time it is the held one.
      const auto held = reference.find(key);
      const std::uint32_t asked =
          held != reference.end() && (rng() & 1U) ? held->second : value(rng);
      table.EraseIfHolds(key, asked);
      if (held != reference.end() && held->second == asked) reference.erase(held);
    } else {
      const std::uint32_t v = value(rng);
      table.Emplace(key, v);
      reference.emplace(key, v);
    }
    ASSERT_EQ(table.size(), reference.size()) << "step " << step;
    // Every key of the range looked up now and then, held or not.
    if (step % 1000 == 999)
      for (std::int64_t x = -40; x <= 40; ++x)
        for (std::int64_t y = -40; y <= 40; ++y) {
          const auto held = reference.find(Key(x, y));
          ASSERT_EQ(table.Find(Key(x, y)),
                    held == reference.end() ? CellTable::kNone : held->second)
              << "step " << step << ", cell " << x << ", " << y;
        }
  }
  EXPECT_GT(reference.size(), 1000u);
}

TEST(CellTable, AKeyHeldKeepsItsFirstValueAndAnErasureOfAnotherValueKeepsIt) {
  CellTable table;
  EXPECT_EQ(table.Find(7), CellTable::kNone);
  table.Emplace(7, 3);
  table.Emplace(7, 4);
  EXPECT_EQ(table.Find(7), 3u);
  table.EraseIfHolds(7, 4);
  EXPECT_EQ(table.Find(7), 3u);
  table.EraseIfHolds(7, 3);
  EXPECT_EQ(table.Find(7), CellTable::kNone);
  EXPECT_EQ(table.size(), 0u);
  EXPECT_THROW(table.Emplace(8, CellTable::kNone), std::invalid_argument);
}

TEST(CellTiles, AgreesWithAMapOverThirtyThousandRandomInsertionsAndErasuresOneByOneAndNineAtATime) {
  std::mt19937_64 rng(20261203);
  // Cells around the origin, so that tiles on both sides of zero and their borders are met.
  std::uniform_int_distribution<std::int64_t> coordinate(-21, 21);
  std::uniform_int_distribution<std::uint32_t> value(0, 1000);
  std::bernoulli_distribution erase(0.4);
  CellTiles tiles;
  std::map<std::pair<std::int64_t, std::int64_t>, std::uint32_t> reference;
  const auto expected = [&](std::int64_t x, std::int64_t y) {
    const auto held = reference.find({x, y});
    return held == reference.end() ? CellTiles::kNone : held->second;
  };
  for (int step = 0; step < 30000; ++step) {
    const std::int64_t x = coordinate(rng), y = coordinate(rng);
    if (erase(rng)) {
      const auto held = reference.find({x, y});
      const std::uint32_t asked =
          held != reference.end() && (rng() & 1U) ? held->second : value(rng);
      tiles.EraseIfHolds(x, y, asked);
      if (held != reference.end() && held->second == asked) reference.erase(held);
    } else {
      const std::uint32_t v = value(rng);
      tiles.Emplace(x, y, v);
      reference.emplace(std::make_pair(x, y), v);
    }
    ASSERT_EQ(tiles.size(), reference.size()) << "step " << step;
    if (step % 1000 != 999) continue;
    for (std::int64_t cx = -22; cx <= 22; ++cx)
      for (std::int64_t cy = -22; cy <= 22; ++cy) {
        ASSERT_EQ(tiles.Find(cx, cy), expected(cx, cy)) << "step " << step;
        // The nine around (cx, cy), and three cells far apart (looked up one by one).
        const std::int64_t ix[3] = {cx - 1, cx, cx + 1}, iy[3] = {cy - 1, cy, cy + 1};
        const std::int64_t fx[3] = {cx - 9, cx, cx + 9}, fy[3] = {cy, cy - 9, cy + 9};
        std::uint32_t held[3][3], far[3][3];
        tiles.FindNine(ix, iy, held);
        tiles.FindNine(fx, fy, far);
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) {
            ASSERT_EQ(held[a][b], expected(ix[a], iy[b])) << "step " << step;
            ASSERT_EQ(far[a][b], expected(fx[a], fy[b])) << "step " << step;
          }
      }
  }
  EXPECT_GT(reference.size(), 500u);
}

TEST(CellTiles, ACellHeldKeepsItsFirstValueAndCellsOfOtherTilesStayApart) {
  CellTiles tiles;
  EXPECT_EQ(tiles.Find(-1, -1), CellTiles::kNone);
  tiles.Emplace(-1, -1, 3);
  tiles.Emplace(-1, -1, 4);
  EXPECT_EQ(tiles.Find(-1, -1), 3u);
  EXPECT_EQ(tiles.Find(-4, -4), CellTiles::kNone);  // the same tile, another cell
  EXPECT_EQ(tiles.Find(3, 3), CellTiles::kNone);    // the same cell within another tile
  tiles.EraseIfHolds(-1, -1, 4);
  EXPECT_EQ(tiles.Find(-1, -1), 3u);
  tiles.Emplace(1LL << 20, 5, 6);
  EXPECT_EQ(tiles.Find(1LL << 20, 5), 6u);
  EXPECT_EQ(tiles.Find(0, 5), CellTiles::kNone);
  EXPECT_EQ(tiles.size(), 2u);
  tiles.EraseIfHolds(-1, -1, 3);
  EXPECT_EQ(tiles.Find(-1, -1), CellTiles::kNone);
  EXPECT_EQ(tiles.size(), 1u);
  EXPECT_THROW(tiles.Emplace(8, 8, CellTiles::kNone), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
