#pragma once
// The most recent values of a stream, held both in arrival order (to forget the oldest) and
// sorted (so that a median or any order statistic is read, not recomputed): a push and a pop move
// at most the window's values once, where a median by selection copies and partitions them all
// at every query. The order statistics are those of the same multiset, so they are bit for bit
// what a selection (std::nth_element) over the arrival-ordered values gives.

#include <algorithm>
#include <cstddef>
#include <deque>
#include <vector>

namespace scanloc {

class SortedWindow {
 public:
  void Push(double value) {
    arrivals_.push_back(value);
    sorted_.insert(std::upper_bound(sorted_.begin(), sorted_.end(), value), value);
  }
  // Forgets the oldest value (none when empty). An equal value is erased from the sorted copy:
  // equal values are interchangeable there.
  void PopOldest() {
    if (arrivals_.empty()) return;
    sorted_.erase(std::lower_bound(sorted_.begin(), sorted_.end(), arrivals_.front()));
    arrivals_.pop_front();
  }
  std::size_t size() const { return arrivals_.size(); }
  bool empty() const { return arrivals_.empty(); }
  // The values, smallest first.
  const std::vector<double>& sorted() const { return sorted_; }
  // The (size / 2)-th smallest value: the upper median, what std::nth_element puts at the middle.
  // 0 when empty.
  double UpperMedian() const { return sorted_.empty() ? 0.0 : sorted_[sorted_.size() / 2]; }

 private:
  std::deque<double> arrivals_;
  std::vector<double> sorted_;
};

}  // namespace scanloc
