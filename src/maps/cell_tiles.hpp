#pragma once
// The point map's de-duplication cells: which point a grid cell (ix, iy) holds. Each inserted
// sample looks up the 3 × 3 cells around it, so this is the point map's busiest table. The cells
// are kept in tiles of 4 × 4, one cache line each, found by their tile's key in a CellTable: the
// nine cells around a sample lie in one to four tiles, looked up once each, instead of nine
// probes of a table of cells at random places in memory.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "cell_table.hpp"

namespace scanloc {

class CellTiles {
 public:
  static constexpr std::uint32_t kNone = CellTable::kNone;

  // The value held for cell (ix, iy), or kNone.
  std::uint32_t Find(std::int64_t ix, std::int64_t iy) const {
    const Tile* tile = TileAt(TileOf(ix), TileOf(iy));
    return tile == nullptr ? kNone : tile->cells[Within(ix, iy)];
  }

  // held[a][b]: the value held for cell (ix[a], iy[b]), or kNone; each tile is looked up once.
  void FindNine(const std::int64_t (&ix)[3], const std::int64_t (&iy)[3],
                std::uint32_t (&held)[3][3]) const {
    const std::int64_t tx = TileOf(*std::min_element(ix, ix + 3));
    const std::int64_t ty = TileOf(*std::min_element(iy, iy + 3));
    if (TileOf(*std::max_element(ix, ix + 3)) - tx > 1 ||
        TileOf(*std::max_element(iy, iy + 3)) - ty > 1) {  // not three neighbours: cell by cell
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) held[a][b] = Find(ix[a], iy[b]);
      return;
    }
    const Tile* tiles[2][2] = {};
    bool looked_up[2][2] = {};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const auto u = static_cast<std::size_t>(TileOf(ix[a]) - tx);
        const auto v = static_cast<std::size_t>(TileOf(iy[b]) - ty);
        if (!looked_up[u][v]) {
          tiles[u][v] =
              TileAt(tx + static_cast<std::int64_t>(u), ty + static_cast<std::int64_t>(v));
          looked_up[u][v] = true;
        }
        held[a][b] = tiles[u][v] == nullptr ? kNone : tiles[u][v]->cells[Within(ix[a], iy[b])];
      }
  }

  // Holds `value` for the cell unless it holds one already (as std::unordered_map::emplace).
  void Emplace(std::int64_t ix, std::int64_t iy, std::uint32_t value) {
    if (value == kNone) throw std::invalid_argument("CellTiles: the value kNone cannot be held");
    const std::int64_t key = TileKey(TileOf(ix), TileOf(iy));
    std::uint32_t index = tile_index_.Find(key);
    if (index == kNone) {
      index = static_cast<std::uint32_t>(tiles_.size());
      tiles_.emplace_back();
      tile_index_.Emplace(key, index);
    }
    std::uint32_t& cell = tiles_[index].cells[Within(ix, iy)];
    if (cell != kNone) return;
    cell = value;
    ++size_;
  }

  // Empties the cell when it holds `value` (a cell taken over by another point stays).
  void EraseIfHolds(std::int64_t ix, std::int64_t iy, std::uint32_t value) {
    const std::uint32_t index = tile_index_.Find(TileKey(TileOf(ix), TileOf(iy)));
    if (index == kNone) return;
    std::uint32_t& cell = tiles_[index].cells[Within(ix, iy)];
    if (cell != value) return;
    cell = kNone;
    --size_;
  }

  // Cells holding a value.
  std::size_t size() const { return size_; }

 private:
  static constexpr std::int64_t kSide = 4;
  struct alignas(64) Tile {
    Tile() { cells.fill(kNone); }
    std::array<std::uint32_t, kSide * kSide> cells;
  };

  // Floor division by the side, for negative indices too.
  static std::int64_t TileOf(std::int64_t i) {
    return i >= 0 ? i / kSide : -((-(i + 1)) / kSide) - 1;
  }
  static std::size_t Within(std::int64_t ix, std::int64_t iy) {
    return static_cast<std::size_t>((ix - kSide * TileOf(ix)) * kSide + (iy - kSide * TileOf(iy)));
  }
  static std::int64_t TileKey(std::int64_t tx, std::int64_t ty) {
    // Unsigned shift: the same bits as tx << 32, without shifting a negative number.
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(tx) << 32) ^
                                     (static_cast<std::uint64_t>(ty) & 0xffffffffULL));
  }
  const Tile* TileAt(std::int64_t tx, std::int64_t ty) const {
    const std::uint32_t index = tile_index_.Find(TileKey(tx, ty));
    return index == kNone ? nullptr : &tiles_[index];
  }

  CellTable tile_index_;  // tile key → index into tiles_
  std::vector<Tile> tiles_;
  std::size_t size_ = 0;
};

}  // namespace scanloc
