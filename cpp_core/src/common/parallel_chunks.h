// A loop over fixed chunks of indices on several threads. Chunks are claimed
// in order from a shared counter, so each index is computed exactly once by
// some thread; a result that depends only on its own index (each thread with
// its own evaluators) is the same for any thread count.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>

namespace tessella {

// Threads for a parallel loop: `requested` if > 0, else the environment
// variable TESSELLA_THREADS if set (> 0), else std::thread::hardware_concurrency();
// never more than the current thread's budget (below).
int worker_threads(int requested = 0);

// The most threads a parallel loop started on this thread may use while the
// object lives (0: no limit). run_chunks gives each of its workers a budget
// of 1 when it runs on several threads, so a loop nested in another (a
// method's own loop inside a face set's faces) does not start more.
class ThreadBudget {
 public:
  explicit ThreadBudget(int threads);
  ~ThreadBudget();
  ThreadBudget(const ThreadBudget&) = delete;
  ThreadBudget& operator=(const ThreadBudget&) = delete;

 private:
  int previous_;
};

class ChunkQueue {
 public:
  ChunkQueue(std::size_t count, std::size_t chunk) : count_(count), chunk_(chunk ? chunk : 1) {}
  // The next chunk [begin, end); false when all are claimed or the loop stops.
  bool next(std::size_t& begin, std::size_t& end);
  // Share of indices claimed so far (for progress).
  double claimed() const;
  std::size_t chunks() const { return (count_ + chunk_ - 1) / chunk_; }
  void stop() { stop_.store(true, std::memory_order_relaxed); }

 private:
  std::size_t count_, chunk_;
  std::atomic<std::size_t> next_{0};
  std::atomic<bool> stop_{false};
};

// Runs worker(on_calling_thread) on min(threads, queue.chunks()) threads, the
// calling thread being one of them (only it may report progress: the progress
// sink is the caller's). Each worker takes chunks from `queue` until it is
// empty. An exception stops the queue, the others finish their chunk, and
// the exception of the lowest chunk that failed is rethrown here (the one a
// single thread would meet first).
void run_chunks(ChunkQueue& queue, int threads, const std::function<void(bool)>& worker);

}  // namespace tessella
