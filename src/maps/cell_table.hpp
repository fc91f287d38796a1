#pragma once
// The point map's tables from a cell's 64-bit key to a 32-bit value: which tile of
// de-duplication cells holds a cell (cell_tiles.hpp), which list holds a search cell's points.
// std::unordered_map divides by a prime and follows a node pointer at every lookup; this table
// keeps its slots in one array (linear probing, Fibonacci hashing, at most half full) and erases
// by shifting the probe run back, so that no tombstone slows later lookups.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace scanloc {

class CellTable {
 public:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  // The value held for `key`, or kNone.
  std::uint32_t Find(std::int64_t key) const {
    if (size_ == 0) return kNone;
    for (std::size_t i = Home(key);; i = (i + 1) & mask_) {
      const Slot& slot = slots_[i];
      if (slot.value == kNone) return kNone;
      if (slot.key == key) return slot.value;
    }
  }

  // Holds `value` for `key` unless the key is held already (as std::unordered_map::emplace).
  void Emplace(std::int64_t key, std::uint32_t value) {
    if (value == kNone) throw std::invalid_argument("CellTable: the value kNone cannot be held");
    if (2 * (size_ + 1) > slots_.size()) Grow();
    std::size_t i = Home(key);
    for (; slots_[i].value != kNone; i = (i + 1) & mask_)
      if (slots_[i].key == key) return;
    slots_[i] = {key, value};
    ++size_;
  }

  // Removes `key` when it holds `value` (a cell taken over by another point stays).
  void EraseIfHolds(std::int64_t key, std::uint32_t value) {
    if (size_ == 0) return;
    std::size_t i = Home(key);
    for (; slots_[i].key != key || slots_[i].value == kNone; i = (i + 1) & mask_)
      if (slots_[i].value == kNone) return;
    if (slots_[i].value != value) return;
    // Backward shift: a later slot of the run moves into the hole unless its home lies
    // cyclically within (hole, slot], where a lookup would no longer pass the hole to reach it.
    for (std::size_t hole = i, j = (i + 1) & mask_;; j = (j + 1) & mask_) {
      if (slots_[j].value == kNone) {
        slots_[hole].value = kNone;
        break;
      }
      const std::size_t home = Home(slots_[j].key);
      const bool stays = hole <= j ? (home > hole && home <= j) : (home > hole || home <= j);
      if (stays) continue;
      slots_[hole] = slots_[j];
      hole = j;
    }
    --size_;
  }

  std::size_t size() const { return size_; }

 private:
  struct Slot {
    std::int64_t key = 0;
    std::uint32_t value = kNone;
  };

  std::size_t Home(std::int64_t key) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ULL) >>
                                    shift_);
  }

  void Grow() {
    std::vector<Slot> old;
    old.swap(slots_);
    const std::size_t capacity = old.empty() ? 64 : 2 * old.size();
    slots_.assign(capacity, Slot{});
    mask_ = capacity - 1;
    shift_ = 64;
    for (std::size_t c = capacity; c > 1; c >>= 1) --shift_;
    size_ = 0;
    for (const Slot& slot : old)
      if (slot.value != kNone) Emplace(slot.key, slot.value);
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  int shift_ = 64;
  std::size_t size_ = 0;
};

}  // namespace scanloc
