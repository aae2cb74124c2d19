// AAF Sec. 6's occluder fill (occluder_fill.h): unoccluded pixels take the
// mean occluder distances of occluded pixels of their object within a disc.
#include <hwy/targets.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "../../../unpinned_instruction_set.h"
#include "aaf/core/methods/aaf/occluder_fill.h"
#include "aaf/core/util/thread_count.h"

using namespace aaf;

namespace {

/// The fill written out from its definition: every pixel of the disc, row by
/// row, summed in float.
FilledOccluders reference_fill(ConstPlaneView d2_min, ConstPlaneView d2_max, ConstPlaneView id, int r) {
    const int width = d2_max.width, height = d2_max.height;
    FilledOccluders f;
    f.d2_min_m.assign(std::size_t(width) * height, 0.0f);
    f.d2_max_m.assign(std::size_t(width) * height, 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            if (has_occluder(d2_max(x, y))) {
                f.d2_min_m[i] = d2_min(x, y);
                f.d2_max_m[i] = d2_max(x, y);
                continue;
            }
            float sum_min = 0, sum_max = 0, count = 0;
            for (int ny = y - r; ny <= y + r; ++ny)
                for (int nx = x - r; nx <= x + r; ++nx) {
                    if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
                    if ((nx - x) * (nx - x) + (ny - y) * (ny - y) > r * r) continue;
                    if (id(nx, ny) != id(x, y) || !has_occluder(d2_max(nx, ny))) continue;
                    sum_min += d2_min(nx, ny);
                    sum_max += d2_max(nx, ny);
                    count += 1.0f;
                }
            if (count > 0) {
                f.d2_min_m[i] = sum_min / count;
                f.d2_max_m[i] = sum_max / count;
            }
        }
    return f;
}

}  // namespace

TEST_CASE("Occluder fill: the disc's mean of same-object occluded neighbours, bit for bit", "[aaf][fill]") {
    const aaf_test::UnpinnedInstructionSet every_target;  // the test walks Highway's targets itself
    // The fill searches bands of rows in parallel, each with r rows of scratch
    // either side: 150 rows are several bands, whose seams the disc must cross,
    // and the band height follows the thread count.
    const auto size = GENERATE(std::make_pair(37, 29), std::make_pair(23, 150));
    const int width = size.first, height = size.second;
    // Interleaved channels (d2min, d2max, id), as an AOV buffer holds them;
    // distances spanning decades, so the float sums' order would show.
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> pixels(std::size_t(width) * height * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float *p = &pixels[(std::size_t(y) * width + x) * 3];
            const float roll = unit(rng);
            const float d2_max = roll < 0.45f  ? 0.0f                                    // unoccluded
                                 : roll < 0.5f ? std::numeric_limits<float>::infinity()  // no hit
                                               : std::pow(10.0f, 6.0f * unit(rng) - 3.0f);
            p[0] = d2_max * unit(rng);
            p[1] = d2_max;
            p[2] = x < 2 * (y % 40) ? 1.0f : 2.0f;
            if (roll > 0.98f) p[2] = std::nanf("");
        }
    auto channel = [&](int c) {
        return ConstPlaneView(pixels.data() + c, width, height, 3, std::ptrdiff_t(width) * 3);
    };
    int filled_somewhere = 0;
    for (const int radius : {0, 1, 3, 5, 8, 20}) {
        const FilledOccluders want = reference_fill(channel(0), channel(1), channel(2), radius);
        // The search is vectorised with runtime dispatch: every instruction set of the build.
        for (const std::int64_t target : hwy::SupportedAndGeneratedTargets())
            for (const int threads : {1, 2, 3}) {
                hwy::SetSupportedTargetsForTest(target);
                FilledOccluders got;
                run_with_threads(threads, [&] {
                    got = fill_occluder_distances(channel(0), channel(1), channel(2), radius);
                });
                INFO(width << "x" << height << ", radius " << radius << ", target " << hwy::TargetName(target)
                           << ", " << threads << " threads");
                REQUIRE(got.d2_max_m.size() == want.d2_max_m.size());
                CHECK(std::memcmp(got.d2_min_m.data(), want.d2_min_m.data(),
                                  want.d2_min_m.size() * sizeof(float)) == 0);
                CHECK(std::memcmp(got.d2_max_m.data(), want.d2_max_m.data(),
                                  want.d2_max_m.size() * sizeof(float)) == 0);
            }
        hwy::SetSupportedTargetsForTest(0);
        for (std::size_t i = 0; i < want.d2_max_m.size(); ++i)
            filled_somewhere += int(!has_occluder(pixels[i * 3 + 1]) && want.d2_max_m[i] > 0);
    }
    CHECK(filled_somewhere > 100);  // the fill really borrowed distances
}
