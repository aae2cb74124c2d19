#include "aaf/core/methods/aaf/occluder_fill.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "aaf/core/methods/aaf/occluder_fill_rows.h"
#include "aaf/core/util/parallel.h"

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

/// Rows of centres searched per band. The bands run in parallel, each
/// preparing its own rows and the r rows either side (2r rows prepared
/// twice per seam), so they are kept short enough for several per thread.
int band_rows(int height, int radius_px) {
    const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
    const int for_balance = (height + 4 * threads - 1) / (4 * threads);
    return std::max({8, 2 * radius_px, std::min(std::max(32, 4 * radius_px), for_balance)});
}

/// One thread's scratch for a band: padded copies of the band's rows and
/// the r rows either side (the search reads them up to (2r+1)^2 times per
/// pixel, so they stay in cache), and the per-row masks below.
struct BandScratch {
    BandScratch(std::size_t padded_width, std::size_t rows, std::size_t near_stride, int width)
        : lender_id(padded_width * rows),
          d2_min_m(padded_width * rows),
          d2_max_m(padded_width * rows),
          occluded(padded_width * rows),
          // Zero past each row's width: a vector of centres reads up to kOccluderSearchPadding beyond.
          occluded_near_in_row(near_stride * rows, 0),
          centre_id(std::size_t(width) + detail::kOccluderSearchPadding),
          occluded_in_window(std::size_t(width)) {}
    std::vector<float> lender_id, d2_min_m, d2_max_m;
    /// Per padded pixel, 1 where it lends its distances.
    std::vector<std::uint8_t> occluded;
    /// Per pixel, whether its row holds an occluded pixel within r columns
    /// (an OR over those columns), so that a window's test is an OR over its
    /// 2r + 1 rows, and the search skips rows with no lender near a vector.
    std::vector<std::uint8_t> occluded_near_in_row;
    /// The searched row: the id each centre looks for (NaN: no search), and
    /// whether its window [x - r, x + r] x [y - r, y + r] holds an occluded pixel.
    std::vector<float> centre_id;
    std::vector<std::uint8_t> occluded_in_window;
};

/// What every band shares: the image's planes, the disc and the scratch's layout.
struct BandLayout {
    ConstPlaneView d2_min, d2_max, object_id;
    int width, height, radius_px, band_rows;
    std::size_t padded_width, near_stride;
    const int *half_width;
};

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Copies image rows [first, last) into the scratch, padded, with only the
/// occluded pixels lending their ids, and marks per row which columns have
/// an occluded pixel within r of them.
void prepare_band_rows(const BandLayout &l, BandScratch &s, int first, int last) {
    // Locals, not members: byte and float stores may alias anything, which
    // would keep the compiler reloading them and from vectorising the loops below.
    const int w = l.width, reach = l.radius_px;
    const std::size_t padded_width = l.padded_width;
    for (int y = first; y < last; ++y) {
        const std::size_t in_scratch = std::size_t(y - first);
        float *const ids = s.lender_id.data() + in_scratch * padded_width;
        float *const mins = s.d2_min_m.data() + in_scratch * padded_width;
        float *const maxs = s.d2_max_m.data() + in_scratch * padded_width;
        // Padding: matches no id, no distances.
        for (const std::size_t begin : {std::size_t(0), std::size_t(reach) + std::size_t(w)}) {
            const std::size_t end = begin == 0 ? std::size_t(reach) : padded_width;
            std::fill(ids + begin, ids + end, kNaN);
            std::fill(mins + begin, mins + end, 0.0f);
            std::fill(maxs + begin, maxs + end, 0.0f);
        }
        copy_row(l.d2_min, y, mins + reach);
        copy_row(l.d2_max, y, maxs + reach);
        copy_row(l.object_id, y, ids + reach);
        // Only occluded pixels lend their distances.
        std::uint8_t *const occluded = s.occluded.data() + in_scratch * padded_width;
        std::fill(occluded, occluded + padded_width, std::uint8_t(0));
        for (int x = reach; x < reach + w; ++x) {
            const bool lends = has_occluder(maxs[x]);
            occluded[x] = std::uint8_t(lends);
            ids[x] = lends ? ids[x] : kNaN;
        }
        std::uint8_t *const near = s.occluded_near_in_row.data() + in_scratch * l.near_stride;
        std::fill(near, near + w, std::uint8_t(0));
        for (int dx = 0; dx <= 2 * reach; ++dx) {
            const std::uint8_t *const from = occluded + dx;
            for (int x = 0; x < w; ++x) near[x] = std::uint8_t(near[x] | from[x]);
        }
    }
}

/// Row `y`'s result: each pixel's own distances where occluded, else the
/// search's mean over its disc's lenders of its id, else 0. The scratch
/// holds image rows from `first`.
void fill_row(const BandLayout &l, BandScratch &s, const detail::OccluderSearch &search, int first, int y,
              FilledOccluders &filled) {
    const int w = l.width, reach = l.radius_px;
    std::uint8_t *const any = s.occluded_in_window.data();
    std::fill(any, any + w, std::uint8_t(0));
    for (int ny = std::max(0, y - reach); ny <= std::min(l.height - 1, y + reach); ++ny) {
        const std::uint8_t *const near =
            s.occluded_near_in_row.data() + std::size_t(ny - first) * l.near_stride;
        for (int x = 0; x < w; ++x) any[x] = std::uint8_t(any[x] | near[x]);
    }
    const std::size_t row = std::size_t(y) * std::size_t(w);
    const std::size_t p = std::size_t(y - first) * l.padded_width + std::size_t(reach);
    const float *const mins = s.d2_min_m.data() + p, *const maxs = s.d2_max_m.data() + p;
    const std::uint8_t *const window = any;
    float *const out_min = filled.d2_min_m.data() + row, *const out_max = filled.d2_max_m.data() + row;
    float *const ids = s.centre_id.data();
    copy_row(l.object_id, y, ids);
    std::fill(ids + w, ids + w + detail::kOccluderSearchPadding, kNaN);
    // One select per loop: GCC turns two selects on one condition into
    // branches and leaves the loop scalar.
    for (int x = 0; x < w; ++x) {
        const float own_min = mins[x];
        out_min[x] = has_occluder(maxs[x]) ? own_min : 0.0f;
    }
    for (int x = 0; x < w; ++x) {
        const float own_max = maxs[x];
        out_max[x] = has_occluder(own_max) ? own_max : 0.0f;
    }
    // NaN: no search (occluded itself, or no occluded pixel in its window).
    for (int x = 0; x < w; ++x) {
        const float id = ids[x];
        ids[x] = has_occluder(maxs[x]) ? kNaN : id;
    }
    for (int x = 0; x < w; ++x) {
        const float id = ids[x];
        ids[x] = window[x] != 0 ? id : kNaN;
    }
    detail::search_occluder_row(search, y, ids, out_min, out_max);
}

/// One band of rows, on one thread, from its own scratch.
void fill_band(const BandLayout &l, BandScratch &s, int band_index, FilledOccluders &filled) {
    const int r = l.radius_px;
    const int band_begin = band_index * l.band_rows, band_end = std::min(l.height, band_begin + l.band_rows);
    // The scratch holds image rows [first, last).
    const int first = std::max(0, band_begin - r), last = std::min(l.height, band_end + r);
    prepare_band_rows(l, s, first, last);
    detail::OccluderSearch search;
    search.lender_id = s.lender_id.data();
    search.d2_min_m = s.d2_min_m.data();
    search.d2_max_m = s.d2_max_m.data();
    search.padded_width = l.padded_width;
    search.pad = r;
    search.width = l.width;
    search.height = l.height;
    search.first_row = first;
    search.half_width = l.half_width;
    search.occluded_near = s.occluded_near_in_row.data();
    search.near_stride = l.near_stride;
    for (int y = band_begin; y < band_end; ++y) fill_row(l, s, search, first, y, filled);
}

}  // namespace

FilledOccluders fill_occluder_distances(ConstPlaneView d2_min, ConstPlaneView d2_max,
                                        ConstPlaneView object_id, int radius_px) {
    const int width = d2_max.width, height = d2_max.height;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    FilledOccluders filled;
    // Not zero-filled: the bands below write every pixel (its own distances, 0, or the search's mean).
    filled.d2_min_m.resize(count);
    filled.d2_max_m.resize(count);
    if (count == 0) return filled;
    const int r = radius_px;
    // The disc's half-width on each row: dx^2 + dy^2 <= r^2.
    std::vector<int> half_width(std::size_t(r) + 1);
    for (int dy = 0; dy <= r; ++dy) {
        int w = 0;
        while ((w + 1) * (w + 1) + dy * dy <= r * r) ++w;
        half_width[std::size_t(dy)] = w;
    }
    BandLayout layout{d2_min,
                      d2_max,
                      object_id,
                      width,
                      height,
                      r,
                      band_rows(height, r),
                      std::size_t(width) + 2 * std::size_t(r) + detail::kOccluderSearchPadding,
                      std::size_t(width) + detail::kOccluderSearchPadding,
                      half_width.data()};
    const int bands = (height + layout.band_rows - 1) / layout.band_rows;
    const std::size_t scratch_rows = std::size_t(std::min(height, layout.band_rows + 2 * r));
    tbb::enumerable_thread_specific<BandScratch> scratches(
        [&] { return BandScratch(layout.padded_width, scratch_rows, layout.near_stride, width); });
    // Each band on one thread, from its own scratch: every pixel's result is
    // its disc's sum in a fixed order, so neither the bands nor the threads
    // change a bit.
    parallel_for_each_index(bands, [&](int band) { fill_band(layout, scratches.local(), band, filled); });
    return filled;
}

}  // namespace aaf
