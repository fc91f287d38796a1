// The point map's de-duplication table against std::unordered_map, over random insertions and
// erasures packed into few home slots (so that probe runs wrap around the array and erasures must
// shift them back).
#include "maps/cell_table.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_map>

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

}  // namespace
}  // namespace scanloc
