#include "core/allocator.h"

#include <malloc.h>

namespace countershade {

void keep_freed_buffers_for_reuse() {
  // Allocations up to 32 MiB (glibc's maximum threshold, above a 1920×1080 RGB float image) come
  // from the heap rather than from mmap, and the heap's free top is trimmed only beyond 2 GiB.
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 0x7fffffff);
}

}  // namespace countershade
