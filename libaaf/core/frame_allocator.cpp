#include "aaf/core/frame_allocator.h"

#include <tbb/scalable_allocator.h>

namespace aaf::detail {

void *frame_allocate(std::size_t bytes) {
    // Cache-line aligned, so SIMD rows start on a line; a zero-sized request still gets a block.
    void *block = scalable_aligned_malloc(bytes == 0 ? 1 : bytes, 64);
    if (block == nullptr) throw std::bad_alloc();
    return block;
}

void frame_deallocate(void *block) noexcept {
    scalable_aligned_free(block);
}

}  // namespace aaf::detail

namespace aaf {

void release_frame_memory() noexcept {
    scalable_allocation_command(TBBMALLOC_CLEAN_ALL_BUFFERS, nullptr);
}

}  // namespace aaf
