#include "aaf/core/occluder_fill.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "aaf/core/occluder_fill_rows.h"
#include "aaf/core/parallel.h"

namespace aaf {

namespace {

/// Rows of centres searched per band; a band's scratch also holds the r rows above and below it.
int band_rows(int radius_px) {
    return std::max(64, 4 * radius_px);
}

}  // namespace

FilledOccluders fill_occluder_distances(ConstPlaneView d2_min, ConstPlaneView d2_max,
                                        ConstPlaneView object_id, int radius_px) {
    const int width = d2_max.width, height = d2_max.height;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    FilledOccluders filled;
    filled.d2_min_m.assign(count, 0.0f);
    filled.d2_max_m.assign(count, 0.0f);
    const int r = radius_px;
    // The disc's half-width on each row: dx^2 + dy^2 <= r^2.
    std::vector<int> half_width(std::size_t(r) + 1);
    for (int dy = 0; dy <= r; ++dy) {
        int w = 0;
        while ((w + 1) * (w + 1) + dy * dy <= r * r) ++w;
        half_width[std::size_t(dy)] = w;
    }
    // The image is searched in bands of rows, one after the other, each
    // band's rows in parallel: the search's scratch (padded copies of the
    // distances and the lenders' ids, which it reads up to (2r+1)^2 times
    // per pixel) holds one band and its r rows either side, not the frame,
    // so it is small, stays in cache and is reused from band to band.
    const std::size_t padded_width = std::size_t(width) + 2 * std::size_t(r) + detail::kOccluderSearchPadding;
    const int band = band_rows(r);
    const std::size_t scratch_rows = std::size_t(std::min(height, band + 2 * r));
    // Not initialised here: each band's rows, padding included, are written before they are read.
    const std::unique_ptr<float[]> lender_id(new float[padded_width * scratch_rows]),
        min_m(new float[padded_width * scratch_rows]), max_m(new float[padded_width * scratch_rows]);
    // Per pixel of the scratch rows, whether its row holds an occluded pixel
    // within r columns (a running count along the row), so that a window's
    // test below is an OR over its 2r + 1 rows: most unoccluded pixels have
    // no occluded pixel in their window and skip the search.
    std::vector<std::uint8_t> occluded_near_in_row(std::size_t(width) * scratch_rows);

    detail::OccluderSearch search;
    search.lender_id = lender_id.get();
    search.d2_min_m = min_m.get();
    search.d2_max_m = max_m.get();
    search.padded_width = padded_width;
    search.pad = r;
    search.width = width;
    search.height = height;
    search.half_width = half_width.data();

    for (int band_begin = 0; band_begin < height; band_begin += band) {
        const int band_end = std::min(height, band_begin + band);
        // The scratch holds image rows [first, last).
        const int first = std::max(0, band_begin - r), last = std::min(height, band_end + r);
        search.first_row = first;
        auto padded = [&](int x, int y) {
            return std::size_t(y - first) * padded_width + std::size_t(x + r);
        };
        parallel_for_rows(last - first, [&](int row_in_scratch) {
            const int y = first + row_in_scratch;
            const std::size_t row_first = std::size_t(row_in_scratch) * padded_width;
            // Padding: matches no id, no distances.
            for (const std::size_t begin : {std::size_t(0), std::size_t(r) + std::size_t(width)}) {
                const std::size_t end = begin == 0 ? std::size_t(r) : padded_width;
                std::fill(lender_id.get() + row_first + begin, lender_id.get() + row_first + end,
                          std::numeric_limits<float>::quiet_NaN());
                std::fill(min_m.get() + row_first + begin, min_m.get() + row_first + end, 0.0f);
                std::fill(max_m.get() + row_first + begin, max_m.get() + row_first + end, 0.0f);
            }
            std::vector<int> occluded_before(std::size_t(width) + 1, 0);
            for (int x = 0; x < width; ++x) {
                const std::size_t i = padded(x, y);
                min_m[i] = d2_min(x, y);
                max_m[i] = d2_max(x, y);
                const bool occluded = has_occluder(max_m[i]);
                lender_id[i] = occluded ? object_id(x, y) : std::numeric_limits<float>::quiet_NaN();
                occluded_before[std::size_t(x) + 1] = occluded_before[std::size_t(x)] + int(occluded);
            }
            // Locals, not the captures: byte stores may alias anything, which would
            // keep the compiler reloading the bounds and from vectorising.
            const int w = width, reach = r;
            const int *const before = occluded_before.data();
            std::uint8_t *const near =
                occluded_near_in_row.data() + std::size_t(row_in_scratch) * std::size_t(w);
            for (int x = 0; x < w; ++x)
                near[x] =
                    std::uint8_t(before[std::min(w, x + reach + 1)] - before[std::max(0, x - reach)] > 0);
        });
        parallel_for_rows(band_end - band_begin, [&](int row_in_band) {
            const int y = band_begin + row_in_band;
            // The id each centre searches for; NaN: no search (occluded itself,
            // or no occluded pixel in its window).
            std::vector<float> centre_id(std::size_t(width) + detail::kOccluderSearchPadding,
                                         std::numeric_limits<float>::quiet_NaN());
            // Whether the window [x - r, x + r] x [y - r, y + r] holds an occluded pixel.
            std::vector<std::uint8_t> occluded_in_window(std::size_t(width), 0);
            {
                const int w = width;  // a local: see above
                std::uint8_t *const any = occluded_in_window.data();
                for (int ny = std::max(0, y - r); ny <= std::min(height - 1, y + r); ++ny) {
                    const std::uint8_t *const near =
                        occluded_near_in_row.data() + std::size_t(ny - first) * std::size_t(w);
                    for (int x = 0; x < w; ++x) any[x] = std::uint8_t(any[x] | near[x]);
                }
            }
            const std::size_t row = std::size_t(y) * width;
            for (int x = 0; x < width; ++x) {
                const std::size_t p = padded(x, y);
                if (has_occluder(max_m[p])) {
                    filled.d2_min_m[row + x] = min_m[p];
                    filled.d2_max_m[row + x] = max_m[p];
                    continue;
                }
                if (occluded_in_window[std::size_t(x)]) centre_id[std::size_t(x)] = object_id(x, y);
            }
            detail::search_occluder_row(search, y, centre_id.data(), filled.d2_min_m.data() + row,
                                        filled.d2_max_m.data() + row);
        });
    }
    return filled;
}

}  // namespace aaf
