// ParallelFor: contiguous chunks in index order that cover the loop once, serial for short
// loops and for loops started inside a loop, errors rethrown to the caller.

#include "scanloc/common/parallel_for.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace scanloc {
namespace {

TEST(ParallelFor, ChunksAreContiguousInOrderAndCoverEveryIndexOnce) {
  const std::size_t count = 10007;
  std::vector<int> visits(count, 0);
  std::mutex mutex;
  std::vector<std::pair<std::size_t, std::size_t>> ranges(ParallelChunkCount(count, 100));
  ParallelFor(count, 100, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) ++visits[i];
    std::lock_guard<std::mutex> lock(mutex);
    ranges[chunk] = {begin, end};
  });
  for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(visits[i], 1) << "index " << i;
  EXPECT_EQ(ranges.front().first, 0u);
  EXPECT_EQ(ranges.back().second, count);
  for (std::size_t c = 1; c < ranges.size(); ++c) EXPECT_EQ(ranges[c].first, ranges[c - 1].second);
}

TEST(ParallelFor, ShortLoopsRunAsOneChunk) {
  EXPECT_EQ(ParallelChunkCount(99, 100), 1u);
  EXPECT_EQ(ParallelChunkCount(0, 100), 1u);
  std::size_t calls = 0;
  ParallelFor(50, 100, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    ++calls;
    EXPECT_EQ(chunk, 0u);
    EXPECT_EQ(begin, 0u);
    EXPECT_EQ(end, 50u);
  });
  EXPECT_EQ(calls, 1u);
}

TEST(ParallelFor, ALoopInsideALoopRunsAndCoversItsRange) {
  std::atomic<std::size_t> total{0};
  ParallelFor(4000, 10, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; i += 1000)
      ParallelFor(1000, 10, [&](std::size_t, std::size_t b, std::size_t e) { total += e - b; });
  });
  EXPECT_EQ(total.load(), 4000u);
}

TEST(ParallelFor, AnExceptionInAnyChunkReachesTheCallerAfterAllChunksFinished) {
  const std::size_t count = 4000;
  const std::size_t chunks = ParallelChunkCount(count, 10);
  std::atomic<std::size_t> finished{0};
  EXPECT_THROW(ParallelFor(count, 10,
                           [&](std::size_t chunk, std::size_t, std::size_t) {
                             ++finished;
                             if (chunk + 1 == chunks) throw std::runtime_error("chunk failed");
                           }),
               std::runtime_error);
  EXPECT_EQ(finished.load(), chunks);
  // The pool is usable again afterwards.
  std::atomic<std::size_t> covered{0};
  ParallelFor(count, 10, [&](std::size_t, std::size_t b, std::size_t e) { covered += e - b; });
  EXPECT_EQ(covered.load(), count);
}

double ProcessCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Sets the pool's size for one test and restores the default after it.
class ParallelThreadsScope {
 public:
  explicit ParallelThreadsScope(std::size_t threads) { SetParallelThreads(threads); }
  ~ParallelThreadsScope() { SetParallelThreads(1); }
};

TEST(ParallelFor, OneThreadRunsEveryChunkOnTheCallingThread) {
  ParallelThreadsScope scope(1);
  EXPECT_EQ(ParallelThreads(), 1u);
  std::set<std::thread::id> threads;
  ParallelFor(100000, 1, [&](std::size_t, std::size_t, std::size_t) {
    threads.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(threads, std::set<std::thread::id>{std::this_thread::get_id()});
}

TEST(ParallelFor, TwoThreadsSplitTheLoopAndGiveTheSerialResult) {
  ParallelThreadsScope scope(2);
  EXPECT_EQ(ParallelThreads(), 2u);
  EXPECT_EQ(ParallelChunkCount(1000, 10), 2u);
  std::vector<double> values(1000);
  ParallelFor(values.size(), 10, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) values[i] = 0.5 * static_cast<double>(i);
  });
  for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], 0.5 * i);
}

// Workers between loops sleep: over 300 ms of idleness after a burst of small loops the whole
// process may use 5 ms of CPU at most (the old pool's workers spun through 20,000 sched_yield
// calls after each loop: 10–40 ms of CPU on an idle machine, far more on a busy one).
TEST(ParallelFor, IdleWorkersBurnNoCpu) {
  ParallelThreadsScope scope(2);
  std::atomic<std::size_t> covered{0};
  for (int loop = 0; loop < 200; ++loop)
    ParallelFor(64, 1, [&](std::size_t, std::size_t b, std::size_t e) { covered += e - b; });
  EXPECT_EQ(covered.load(), 200u * 64u);
  const double before = ProcessCpuSeconds();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_LT(ProcessCpuSeconds() - before, 0.005);
}

}  // namespace
}  // namespace scanloc
