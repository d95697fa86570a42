#include "common/parallel_chunks.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <limits>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace tessella {

namespace {
thread_local int tls_budget = 0;

// The chunk a run_chunks worker on this thread claimed last from its queue
// (a nested loop on the thread installs its own and restores this one).
struct Claim {
  const ChunkQueue* queue = nullptr;
  std::size_t chunk = std::numeric_limits<std::size_t>::max();
};
thread_local Claim* tls_claim = nullptr;

int unlimited_threads(int requested) {
  if (requested > 0) return requested;
  if (const char* env = std::getenv("TESSELLA_THREADS")) {
    const int n = std::atoi(env);
    if (n > 0) return n;
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(hw) : 1;
}
}  // namespace

ThreadBudget::ThreadBudget(int threads) : previous_(tls_budget) {
  if (threads > 0) tls_budget = tls_budget > 0 ? std::min(tls_budget, threads) : threads;
}
ThreadBudget::~ThreadBudget() { tls_budget = previous_; }

int worker_threads(int requested) {
  const int n = unlimited_threads(requested);
  return tls_budget > 0 ? std::min(n, tls_budget) : n;
}

bool ChunkQueue::next(std::size_t& begin, std::size_t& end) {
  if (stop_.load(std::memory_order_relaxed)) return false;
  const std::size_t c = next_.fetch_add(1, std::memory_order_relaxed);
  if (c >= chunks()) return false;
  if (tls_claim && tls_claim->queue == this) tls_claim->chunk = c;
  begin = c * chunk_;
  end = std::min(count_, begin + chunk_);
  return true;
}

double ChunkQueue::claimed() const {
  if (count_ == 0) return 1.0;
  const std::size_t c = std::min(next_.load(std::memory_order_relaxed), chunks());
  return std::min(1.0, double(c * chunk_) / double(count_));
}

void run_chunks(ChunkQueue& queue, int threads, const std::function<void(bool)>& worker) {
  const std::size_t n =
      std::max<std::size_t>(1, std::min<std::size_t>(std::max(threads, 1), queue.chunks()));
  // Where several chunks fail, the one of the lowest index is rethrown: the
  // chunks are claimed in order, so every chunk below a failing one was
  // claimed and runs to its end (or fails), and the failure reported is the
  // one a single thread meets first, whatever the threads' timing (a face
  // set with two faces its method refuses names the same face on any thread
  // count).
  std::exception_ptr failure;
  std::size_t failed_chunk = std::numeric_limits<std::size_t>::max();
  std::mutex failure_mutex;
  // Each worker of a loop on several threads runs nested loops on its own.
  const int inner = n > 1 ? 1 : tls_budget;
  auto guarded = [&](bool calling) {
    const ThreadBudget budget(inner);
    Claim claim{&queue};
    Claim* const outer = tls_claim;
    tls_claim = &claim;
    try {
      worker(calling);
    } catch (...) {
      queue.stop();
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure || claim.chunk < failed_chunk) {
        failure = std::current_exception();
        failed_chunk = claim.chunk;
      }
    }
    tls_claim = outer;
  };
  std::vector<std::thread> others;
  others.reserve(n - 1);
  for (std::size_t t = 1; t < n; ++t) {
    try {
      others.emplace_back(guarded, false);
    } catch (const std::system_error&) {
      break;  // no more threads: the ones running take the remaining chunks
    }
  }
  guarded(true);
  for (std::thread& t : others) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace tessella
