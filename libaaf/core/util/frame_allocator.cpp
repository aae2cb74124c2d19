#include "aaf/core/util/frame_allocator.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include <tbb/scalable_allocator.h>

#if defined(__linux__)
#include <sys/mman.h>
#endif

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
constexpr std::size_t kAlignment = 64;                   // a cache line, so SIMD rows start on one
constexpr std::size_t kHugePage = std::size_t(2) << 20;  // x86-64's and most ARM64 kernels'

#if defined(__linux__) && defined(MADV_HUGEPAGE)

/// Asks for transparent huge pages over the whole 2 MiB pages inside a
/// frame-sized block, before it is first touched: one page fault per 2 MiB
/// instead of 512, where the system leaves huge pages to madvise (as on the
/// benchmark machine: first touching 40 MiB took 117 ms in 4 KiB pages,
/// 3 ms in huge pages). Advice only: where it is refused, the block is
/// still usable in small pages.
void advise_huge_pages(void *block, std::size_t size) {
    const auto begin = reinterpret_cast<std::uintptr_t>(block);
    const std::uintptr_t first = (begin + kHugePage - 1) / kHugePage * kHugePage;
    const std::uintptr_t last = (begin + size) / kHugePage * kHugePage;
    if (last > first) ::madvise(reinterpret_cast<void *>(first), last - first, MADV_HUGEPAGE);
}
#else
void advise_huge_pages(void *, std::size_t) {}
#endif
}  // namespace

void *frame_allocate(std::size_t bytes) {
    // Whole cache lines (aligned_alloc's rule); a zero-sized request still gets one.
    const std::size_t size = (std::max<std::size_t>(bytes, 1) + kAlignment - 1) / kAlignment * kAlignment;
#ifdef AAF_FRAMES_FROM_SYSTEM
    void *block = std::aligned_alloc(kAlignment, size);
#else
    // A block of at least a huge page starts on one, so all of it can be in huge pages.
    void *block = scalable_aligned_malloc(size, size >= kHugePage ? kHugePage : kAlignment);
#endif
    if (block == nullptr) throw std::bad_alloc();
    advise_huge_pages(block, size);
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
