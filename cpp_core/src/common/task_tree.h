// A tree of tasks on several threads: each task may push children, and any
// idle thread takes the newest pending one. For a recursive split whose
// leaves write their own results (the grid cut by the trim: a part of the
// domain cut in halves down to single cells), so the results are the same
// for any thread count and any order the tasks ran in.
#pragma once

#include <condition_variable>
#include <mutex>
#include <utility>
#include <vector>

#include "common/parallel_chunks.h"

namespace tessella {

// Runs process(task, push) for `root` and every task pushed since, on up to
// `threads` threads (the calling thread one of them); push(Task) may be
// called any number of times from process. The first exception stops every
// thread once its current task ends and is rethrown here.
template <class Task, class Process>
void run_task_tree(Task root, int threads, const Process& process) {
  std::vector<Task> pending;
  pending.push_back(std::move(root));
  std::mutex mutex;
  std::condition_variable changed;
  int busy = 0;
  bool failed = false;
  auto push = [&](Task child) {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      pending.push_back(std::move(child));
    }
    changed.notify_one();
  };
  ChunkQueue workers(static_cast<std::size_t>(std::max(threads, 1)), 1);
  run_chunks(workers, threads, [&](bool) {
    std::size_t begin = 0, end = 0;
    if (!workers.next(begin, end)) return;
    for (;;) {
      Task task;
      {
        std::unique_lock<std::mutex> lock(mutex);
        // Idle until there is a task, or none is pending nor can come.
        changed.wait(lock, [&] { return failed || !pending.empty() || busy == 0; });
        if (failed || pending.empty()) return;
        task = std::move(pending.back());
        pending.pop_back();
        ++busy;
      }
      try {
        process(task, push);
      } catch (...) {
        {
          const std::lock_guard<std::mutex> lock(mutex);
          failed = true;
          --busy;
        }
        changed.notify_all();
        throw;
      }
      {
        const std::lock_guard<std::mutex> lock(mutex);
        --busy;
      }
      changed.notify_all();
    }
  });
}

}  // namespace tessella
