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

/// Copies row `y` of `plane` to `to` (width floats).
void copy_row(ConstPlaneView plane, int y, float *to) {
    const float *const from = &plane(0, y);
    if (plane.pixel_stride == 1) {
        std::copy(from, from + plane.width, to);
        return;
    }
    for (int x = 0; x < plane.width; ++x) to[x] = from[std::ptrdiff_t(x) * plane.pixel_stride];
}

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
    // Not zero-filled: the rows below write every pixel (its own distances, 0, or the search's mean).
    filled.d2_min_m.resize(count);
    filled.d2_max_m.resize(count);
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
    // within r columns (an OR over those columns), so that a window's test
    // below is an OR over its 2r + 1 rows: most unoccluded pixels have no
    // occluded pixel in their window and skip the search, and the search
    // skips rows that hold no lender for any of a vector's centres.
    const std::size_t near_stride = std::size_t(width) + detail::kOccluderSearchPadding;
    std::vector<std::uint8_t> occluded_near_in_row(near_stride * scratch_rows, 0);
    // Per padded pixel of the scratch rows, 1 where it lends its distances.
    std::vector<std::uint8_t> occluded_scratch(padded_width * scratch_rows);

    detail::OccluderSearch search;
    search.lender_id = lender_id.get();
    search.d2_min_m = min_m.get();
    search.d2_max_m = max_m.get();
    search.padded_width = padded_width;
    search.pad = r;
    search.width = width;
    search.height = height;
    search.half_width = half_width.data();
    search.occluded_near = occluded_near_in_row.data();
    search.near_stride = near_stride;

    for (int band_begin = 0; band_begin < height; band_begin += band) {
        const int band_end = std::min(height, band_begin + band);
        // The scratch holds image rows [first, last).
        const int first = std::max(0, band_begin - r), last = std::min(height, band_end + r);
        search.first_row = first;
        parallel_for_rows(last - first, [&](int row_in_scratch) {
            const int y = first + row_in_scratch;
            // Locals, not the captures: byte and float stores may alias
            // anything, which would keep the compiler reloading them and
            // from vectorising the loops below.
            const int w = width, reach = r;
            float *const ids = lender_id.get() + std::size_t(row_in_scratch) * padded_width;
            float *const mins = min_m.get() + std::size_t(row_in_scratch) * padded_width;
            float *const maxs = max_m.get() + std::size_t(row_in_scratch) * padded_width;
            // Padding: matches no id, no distances.
            for (const std::size_t begin : {std::size_t(0), std::size_t(reach) + std::size_t(w)}) {
                const std::size_t end = begin == 0 ? std::size_t(reach) : padded_width;
                std::fill(ids + begin, ids + end, std::numeric_limits<float>::quiet_NaN());
                std::fill(mins + begin, mins + end, 0.0f);
                std::fill(maxs + begin, maxs + end, 0.0f);
            }
            copy_row(d2_min, y, mins + reach);
            copy_row(d2_max, y, maxs + reach);
            copy_row(object_id, y, ids + reach);
            // Only occluded pixels lend their distances.
            std::uint8_t *const occluded =
                occluded_scratch.data() + std::size_t(row_in_scratch) * padded_width;
            std::fill(occluded, occluded + padded_width, std::uint8_t(0));
            for (int x = reach; x < reach + w; ++x) {
                const bool lends = has_occluder(maxs[x]);
                occluded[x] = std::uint8_t(lends);
                ids[x] = lends ? ids[x] : std::numeric_limits<float>::quiet_NaN();
            }
            // Per pixel, whether its row holds an occluded pixel within r columns.
            std::uint8_t *const near =
                occluded_near_in_row.data() + std::size_t(row_in_scratch) * near_stride;
            std::fill(near, near + w, std::uint8_t(0));
            for (int dx = 0; dx <= 2 * reach; ++dx) {
                const std::uint8_t *const from = occluded + dx;
                for (int x = 0; x < w; ++x) near[x] = std::uint8_t(near[x] | from[x]);
            }
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
                        occluded_near_in_row.data() + std::size_t(ny - first) * near_stride;
                    for (int x = 0; x < w; ++x) any[x] = std::uint8_t(any[x] | near[x]);
                }
            }
            const std::size_t row = std::size_t(y) * width;
            {
                const int w = width;  // locals: see above
                const std::size_t p = std::size_t(y - first) * padded_width + std::size_t(r);
                const float *const mins = min_m.get() + p, *const maxs = max_m.get() + p;
                float *const out_min = filled.d2_min_m.data() + row, *const out_max =
                                                                         filled.d2_max_m.data() + row;
                const std::uint8_t *const any = occluded_in_window.data();
                float *const ids = centre_id.data();
                copy_row(object_id, y, ids);
                for (int x = 0; x < w; ++x) {
                    const bool own = has_occluder(maxs[x]);
                    out_min[x] = own ? mins[x] : 0.0f;
                    out_max[x] = own ? maxs[x] : 0.0f;
                    // NaN: no search (occluded itself, or no occluded pixel in its window).
                    ids[x] = !own && any[x] ? ids[x] : std::numeric_limits<float>::quiet_NaN();
                }
            }
            detail::search_occluder_row(search, y, centre_id.data(), filled.d2_min_m.data() + row,
                                        filled.d2_max_m.data() + row);
        });
    }
    return filled;
}

}  // namespace aaf
