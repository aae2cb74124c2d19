#include "aaf/core/frame_allocator.h"

#include <algorithm>
#include <cstdlib>

#include <tbb/scalable_allocator.h>

// Under AddressSanitizer the system allocator serves frames, so that its
// checks cover them (it does not see oneTBB's pools).
#if defined(__SANITIZE_ADDRESS__)
#define AAF_FRAMES_FROM_SYSTEM 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define AAF_FRAMES_FROM_SYSTEM 1
#endif
#endif

namespace aaf::detail {

namespace {
constexpr std::size_t kAlignment = 64;  // a cache line, so SIMD rows start on one
}

void *frame_allocate(std::size_t bytes) {
    // Whole cache lines (aligned_alloc's rule); a zero-sized request still gets one.
    const std::size_t size = (std::max<std::size_t>(bytes, 1) + kAlignment - 1) / kAlignment * kAlignment;
#ifdef AAF_FRAMES_FROM_SYSTEM
    void *block = std::aligned_alloc(kAlignment, size);
#else
    void *block = scalable_aligned_malloc(size, kAlignment);
#endif
    if (block == nullptr) throw std::bad_alloc();
    return block;
}

void frame_deallocate(void *block) noexcept {
#ifdef AAF_FRAMES_FROM_SYSTEM
    std::free(block);
#else
    scalable_aligned_free(block);
#endif
}

}  // namespace aaf::detail

namespace aaf {

void release_frame_memory() noexcept {
#ifndef AAF_FRAMES_FROM_SYSTEM
    scalable_allocation_command(TBBMALLOC_CLEAN_ALL_BUFFERS, nullptr);
#endif
}

}  // namespace aaf
