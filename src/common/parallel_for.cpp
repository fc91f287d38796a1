#include "scanloc/common/parallel_for.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace scanloc {
namespace {

// Workers that live as long as the program: starting a thread for each loop costs more than
// the loops it would share (measured: a session ran slower, its system time up 14×). One job at
// a time; a loop started while another runs (from a worker, or another thread) runs serially.
class WorkerPool {
 public:
  explicit WorkerPool(std::size_t workers) {
    for (std::size_t i = 0; i < workers; ++i) threads_.emplace_back([this, i] { Work(i + 1); });
  }
  ~WorkerPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& thread : threads_) thread.join();
  }
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  std::size_t size() const { return threads_.size() + 1; }

  // Runs chunk(c) for c in [0, chunks), chunks ≤ size(), the caller taking chunk 0. False, without
  // running anything, when the pool is busy with another loop.
  bool Run(std::size_t chunks, const std::function<void(std::size_t)>& chunk) {
    std::unique_lock<std::mutex> busy(run_mutex_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = &chunk;
      chunks_ = chunks;
      pending_.store(chunks - 1);
      generation_.fetch_add(1);
    }
    wake_.notify_all();
    chunk(0);
    // The other chunks are about as long as this one: spin briefly before sleeping.
    for (int spin = 0; spin < kSpins && pending_.load() != 0; ++spin) std::this_thread::yield();
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return pending_.load() == 0; });
    job_ = nullptr;
    return true;
  }

 private:
  // A session runs a few loops per scan in quick succession; a worker that slept would wake up
  // later than the loop takes (tens of µs on a virtual machine), so it spins a while first.
  static constexpr int kSpins = 20000;

  void Work(std::size_t id) {
    std::uint64_t seen = 0;
    for (;;) {
      for (int spin = 0; spin < kSpins && generation_.load() == seen; ++spin)
        std::this_thread::yield();
      const std::function<void(std::size_t)>* job = nullptr;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || generation_.load() != seen; });
        if (stopping_) return;
        seen = generation_.load();
        if (id >= chunks_) continue;
        job = job_;
      }
      (*job)(id);
      std::lock_guard<std::mutex> lock(mutex_);
      if (pending_.fetch_sub(1) == 1) done_.notify_one();
    }
  }

  std::mutex run_mutex_;  // one loop at a time
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t)>* job_ = nullptr;
  std::size_t chunks_ = 0;
  std::atomic<std::size_t> pending_{0};
  std::atomic<std::uint64_t> generation_{0};
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

WorkerPool& Pool() {
  static WorkerPool pool(std::max(1u, std::thread::hardware_concurrency()) - 1);
  return pool;
}

}  // namespace

std::size_t ParallelChunkCount(std::size_t count, std::size_t min_chunk) {
  const std::size_t cores = Pool().size();
  const std::size_t by_size = count / std::max<std::size_t>(1, min_chunk);
  return std::max<std::size_t>(1, std::min(cores, by_size));
}

void ParallelFor(std::size_t count, std::size_t min_chunk,
                 const std::function<void(std::size_t, std::size_t, std::size_t)>& body) {
  const std::size_t chunks = ParallelChunkCount(count, min_chunk);
  std::vector<std::exception_ptr> errors(chunks);
  const std::function<void(std::size_t)> chunk = [&](std::size_t c) {
    try {
      body(c, count * c / chunks, count * (c + 1) / chunks);
    } catch (...) {
      errors[c] = std::current_exception();
    }
  };
  if (chunks == 1 || !Pool().Run(chunks, chunk))
    for (std::size_t c = 0; c < chunks; ++c) chunk(c);
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace scanloc
