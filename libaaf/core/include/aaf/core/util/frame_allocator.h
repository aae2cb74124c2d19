#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace aaf {

namespace detail {
/// Frame-sized blocks from oneTBB's scalable allocator, 64-byte aligned.
/// It keeps freed large blocks for reuse, so a process that filters frame
/// after frame does not fault each frame's scratch planes in afresh (page
/// faults and the kernel's zeroing of fresh pages were a fifth of the AAF
/// filter at 11 Mpixel, and grew with the frame). Throws std::bad_alloc.
void *frame_allocate(std::size_t bytes);
void frame_deallocate(void *block) noexcept;
}  // namespace detail

/// Returns the freed frame blocks the allocator keeps for reuse to the
/// system, e.g. after a frame is filtered and before its output is written,
/// so they do not add to the writer's peak memory. The next frame's blocks
/// are then fresh memory again.
void release_frame_memory() noexcept;

/// A standard allocator over detail::frame_allocate(), for per-frame planes.
template <typename T>
struct FrameAllocator {
    using value_type = T;
    FrameAllocator() = default;
    template <typename U>
    FrameAllocator(const FrameAllocator<U> &) noexcept {}
    T *allocate(std::size_t n) { return static_cast<T *>(detail::frame_allocate(n * sizeof(T))); }
    void deallocate(T *p, std::size_t) noexcept { detail::frame_deallocate(p); }
    template <typename U>
    bool operator==(const FrameAllocator<U> &) const noexcept {
        return true;
    }
    template <typename U>
    bool operator!=(const FrameAllocator<U> &) const noexcept {
        return false;
    }
};

/// A plane (or any per-pixel array) of one frame.
template <typename T>
using FrameVector = std::vector<T, FrameAllocator<T>>;

/// A FrameAllocator whose construct() without a value default-initialises,
/// so a FramePlane's resize(n) leaves new numbers uninitialised: no serial
/// zero-fill of a plane that is about to be written in full.
template <typename T>
struct FramePlaneAllocator : FrameAllocator<T> {
    template <typename U>
    struct rebind {
        using other = FramePlaneAllocator<U>;
    };
    FramePlaneAllocator() = default;
    template <typename U>
    FramePlaneAllocator(const FramePlaneAllocator<U> &) noexcept {}
    template <typename U>
    void construct(U *p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void *>(p)) U;
    }
    template <typename U, typename... Args>
    void construct(U *p, Args &&...args) {
        ::new (static_cast<void *>(p)) U(std::forward<Args>(args)...);
    }
};

/// A plane of one frame whose resize(n) does not initialise its numbers;
/// assign(n, value) and the other members behave as FrameVector's.
template <typename T>
using FramePlane = std::vector<T, FramePlaneAllocator<T>>;

/// Frees a frame_allocate() block; for uninitialised scratch planes.
struct FrameDeleter {
    void operator()(void *block) const noexcept { detail::frame_deallocate(block); }
};

/// An uninitialised plane of `count` floats.
using FrameScratch = std::unique_ptr<float[], FrameDeleter>;
inline FrameScratch make_frame_scratch(std::size_t count) {
    return FrameScratch(static_cast<float *>(detail::frame_allocate(count * sizeof(float))));
}

}  // namespace aaf
