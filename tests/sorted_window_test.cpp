// The sorted window: its order statistics are those a selection over the same recent values gives,
// through pushes and pops, ties included; and the laser signature's bound read from it is bit for
// bit the selection-based median + k · 1.4826 · MAD.

#include "scanloc/common/sorted_window.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <random>
#include <vector>

#include "scanloc/likelihood/laser_signature.hpp"

namespace scanloc {
namespace {

// What the median by selection gave: the (n / 2)-th smallest.
double UpperMedianBySelection(const std::deque<double>& values) {
  std::vector<double> copy(values.begin(), values.end());
  std::nth_element(copy.begin(), copy.begin() + static_cast<std::ptrdiff_t>(copy.size() / 2),
                   copy.end());
  return copy[copy.size() / 2];
}

// The median (mean of the two middle values when even) by selection.
double MedianBySelection(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + mid));
}

// Values on a coarse grid, so that ties are frequent.
double Draw(std::mt19937& random) {
  return 0.01 * std::uniform_int_distribution<int>(0, 40)(random);
}

TEST(SortedWindow, TheUpperMedianIsTheSelectionsThroughThirtyThousandPushesAndPops) {
  std::mt19937 random(7);
  SortedWindow window;
  std::deque<double> reference;
  EXPECT_EQ(window.UpperMedian(), 0.0);
  for (int step = 0; step < 30000; ++step) {
    const double value = Draw(random);
    window.Push(value);
    reference.push_back(value);
    const std::size_t limit = 1 + static_cast<std::size_t>(step / 3000) * 50;  // 1 … 451
    while (reference.size() > limit) {
      window.PopOldest();
      reference.pop_front();
    }
    ASSERT_EQ(window.size(), reference.size());
    ASSERT_EQ(window.UpperMedian(), UpperMedianBySelection(reference)) << "step " << step;
    ASSERT_TRUE(std::is_sorted(window.sorted().begin(), window.sorted().end()));
  }
}

TEST(SortedWindow, PoppingAnEmptyWindowDoesNothing) {
  SortedWindow window;
  window.PopOldest();
  EXPECT_TRUE(window.empty());
  window.Push(2.0);
  window.Push(1.0);
  window.PopOldest();  // the 2, not the smallest
  ASSERT_EQ(window.size(), 1u);
  EXPECT_EQ(window.UpperMedian(), 1.0);
}

TEST(LaserSignature, TheBoundFromTheSortedWindowIsBitForBitTheSelectionsOverOddAndEvenWindows) {
  for (const int window_size : {1, 2, 5, 10, 11, 64}) {
    LaserSignature signature({window_size, 1, 3.0});
    std::mt19937 random(static_cast<unsigned>(window_size));
    std::deque<double> kept;
    for (int step = 0; step < 400; ++step) {
      // Expected values on a grid with noise, so both ties and distinct values occur.
      const double ev = step % 3 == 0 ? Draw(random) : Draw(random) + 1e-3 * (step % 7);
      LikelihoodTestResult confirmed;
      confirmed.valid_pairs = confirmed.match_pairs = 10;
      confirmed.expect_value_m = ev;
      confirmed.histogram = {1, 1};
      signature.Add(confirmed);
      kept.push_back(ev);
      if (kept.size() > static_cast<std::size_t>(window_size)) kept.pop_front();
      std::vector<double> values(kept.begin(), kept.end());
      const double median = MedianBySelection(values);
      for (double& v : values) v = std::abs(v - median);
      const double expected = std::max(0.0, median + 3.0 * (1.4826 * MedianBySelection(values)));
      ASSERT_EQ(signature.ExpectValueBound(0.0), expected)
          << "window " << window_size << ", step " << step;
    }
  }
}

}  // namespace
}  // namespace scanloc
