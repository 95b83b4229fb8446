#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace countershade {

void parallel_ranges(size_t n, int threads, const std::function<void(size_t, size_t)>& body,
                     size_t grain) {
  run_with_threads(threads, [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                      [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
  });
}

}  // namespace countershade
