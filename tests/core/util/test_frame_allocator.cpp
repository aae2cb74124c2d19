// Frame-sized planes from oneTBB's scalable allocator (frame_allocator.h).
#include <catch2/catch.hpp>
#include <cstdint>
#include <numeric>

#include "aaf/core/util/frame_allocator.h"

using namespace aaf;

TEST_CASE("Frame allocator: aligned blocks that keep their values, reused after release", "[core][memory]") {
    for (const std::size_t count : {std::size_t(1), std::size_t(1000), std::size_t(3) << 20}) {
        FrameVector<float> plane(count, 2.5f);
        // Cache-line aligned, so SIMD rows of a plane start on a line.
        CHECK(reinterpret_cast<std::uintptr_t>(plane.data()) % 64 == 0);
        std::iota(plane.begin(), plane.end(), 0.0f);
        CHECK(plane[count - 1] == float(count - 1));
        FrameScratch scratch = make_frame_scratch(count);
        CHECK(reinterpret_cast<std::uintptr_t>(scratch.get()) % 64 == 0);
        scratch[count - 1] = 7.0f;
        CHECK(scratch[count - 1] == 7.0f);
    }
    // An empty scratch plane is still a block of its own.
    const FrameScratch empty = make_frame_scratch(0), other = make_frame_scratch(0);
    CHECK(empty.get() != nullptr);
    CHECK(empty.get() != other.get());
    // Freed blocks returned to the system; allocation works as before.
    release_frame_memory();
    FrameVector<int> after(4096, 3);
    CHECK(std::accumulate(after.begin(), after.end(), 0) == 3 * 4096);
}
