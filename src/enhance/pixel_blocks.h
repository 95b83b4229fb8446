#pragma once
// Parallel loops over a view's pixels in blocks of kPixelBlock, so that vectors of pixels keep
// their buffers' alignment, which the CIELAB conversion's streaming stores need.

#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <functional>

#include "core/parallel.h"

namespace countershade {

inline constexpr size_t kPixelBlock = 64;

// Runs body(begin, end) over [0, n) in parallel, in ranges that start at multiples of
// kPixelBlock. Each range's streaming stores are complete (sfence) before this returns.
inline void parallel_pixel_blocks(size_t n, int threads,
                                  const std::function<void(size_t, size_t)>& body) {
  parallel_ranges((n + kPixelBlock - 1) / kPixelBlock, threads,
                  [&](size_t begin, size_t end) {
                    body(begin * kPixelBlock, std::min(n, end * kPixelBlock));
                    _mm_sfence();
                  },
                  4096 / kPixelBlock);
}

}  // namespace countershade
