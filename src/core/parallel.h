#pragma once
// Parallel loops on a chosen number of threads (TBB), the one place that turns "0 = all cores"
// into an arena.

#include <tbb/task_arena.h>

#include <cstddef>
#include <functional>

namespace countershade {

// `threads` > 0, or every core the process may use.
inline int worker_count(int threads) {
  return threads > 0 ? threads : tbb::this_task_arena::max_concurrency();
}

// Runs `work` inside an arena of worker_count(threads) threads, so nested TBB loops use that many.
template <class Work>
void run_with_threads(int threads, Work&& work) {
  tbb::task_arena arena(worker_count(threads));
  arena.execute(std::forward<Work>(work));
}

// Runs `body(begin, end)` over [0, n) on worker_count(threads) threads, in chunks of at least
// `grain`.
void parallel_ranges(size_t n, int threads, const std::function<void(size_t, size_t)>& body,
                     size_t grain = 1);

}  // namespace countershade
