#pragma once
// Memory allocator settings for the whole process.

namespace countershade {

// countershade allocates and frees image-sized buffers (tens of MB) for every view and λ. By
// default glibc hands buffers of that size back to the kernel on free, and the next allocation
// faults every page in again, zeroed. On the reference VM that costs about 0.7 ms per MB, more
// than the image work itself. This keeps freed buffers in the heap for reuse instead. Call once,
// at the start of main().
void keep_freed_buffers_for_reuse();

}  // namespace countershade
