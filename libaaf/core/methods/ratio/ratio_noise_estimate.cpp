// The total-variation noise estimate of the ratio estimator (Heitz, Hill,
// McGuire 2018, Sec. 4.2, ratio estimator Eq. 29).
#include "aaf/core/methods/ratio/ratio_noise_estimate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/methods/ratio/ratio_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

void check_same_size(ConstPlaneView a, ConstPlaneView b, const char *what) {
    if (!a.valid() || !b.valid() || a.width != b.width || a.height != b.height)
        throw Error(std::string("ratio noise estimate: ") + what + " is missing or has another size");
}

/// out[x] = 1 where any of in[x - radius .. x + radius] (clipped to
/// [0, count)) is non-zero, else 0: one pass per offset, so it vectorises
/// (__restrict: bytes may alias anything, these do not).
void dilate(const unsigned char *__restrict in, int count, int radius, unsigned char *__restrict out) {
    std::fill_n(out, count, 0);
    for (int offset = -radius; offset <= radius; ++offset)
        for (int x = std::max(0, -offset); x < std::min(count, count - offset); ++x) out[x] |= in[x + offset];
}

/// Per row, 1 where pixels [x - radius, x + radius] of the row hold a pixel
/// of `w` (width x height, rows `row_floats` apart) that differs from its
/// right or lower neighbour, else 0. A (2 radius + 1)^2 window with two
/// values holds two neighbours that differ, so OR-ing 2 radius + 1 of these
/// rows (active_row) tells whether the window varies.
FramePlane<unsigned char> varying_along_rows(const float *w, std::size_t row_floats, int width, int height,
                                             int radius) {
    FramePlane<unsigned char> out;
    out.resize(std::size_t(width) * std::size_t(height));  // written in full
    parallel_for_rows(height, [&](int y) {
        const int n = width;  // a local: a byte store might alias a captured value, not a local
        const float *row = w + std::size_t(y) * row_floats;
        const bool has_below = y + 1 < height;
        const float *below = has_below ? row + row_floats : row;  // read, then ignored, on the last row
        thread_local std::vector<unsigned char> flags;
        flags.resize(std::size_t(n));
        unsigned char *__restrict flag = flags.data();
        // a != b holds where either is NaN: NaN differs from everything.
        for (int x = 0; x + 1 < n; ++x) flag[x] = (row[x] != row[x + 1]) | (has_below & (row[x] != below[x]));
        flag[n - 1] = has_below & (row[n - 1] != below[n - 1]);
        dilate(flag, n, radius, &out[std::size_t(y) * std::size_t(width)]);
    });
    return out;
}

/// Row `y` of the pixels whose (2 radius + 1)^2 window varies: the OR of
/// rows y - radius .. y + radius (clipped) of varying_along_rows' plane.
void active_row(const FramePlane<unsigned char> &along_rows, int width, int height, int radius, int y,
                unsigned char *__restrict row) {
    const int n = width, first = std::max(0, y - radius), last = std::min(height - 1, y + radius);
    std::fill_n(row, n, 0);
    for (int ty = first; ty <= last; ++ty) {
        const unsigned char *__restrict from = &along_rows[std::size_t(ty) * std::size_t(n)];
        for (int x = 0; x < n; ++x) row[x] |= from[x];
    }
}

/// W_N of `count` adjacent pixels (ratio estimator Eq. 23); W_N = 1 where
/// U_N is ~0 (Sec. 4.2), non-finite S_N and U_N read as 0.
void weighted_shadow_row(const float *__restrict s_n, const float *__restrict u_n, int count,
                         float *__restrict w) {
    for (int x = 0; x < count; ++x) {
        const float s = std::isfinite(s_n[x]) ? s_n[x] : 0.0f;
        const float u = std::isfinite(u_n[x]) ? u_n[x] : 0.0f;
        w[x] = u > 0 ? std::clamp(s / u, 0.0f, 1.0f) : 1.0f;
    }
}

/// W_N's value at a tap: non-finite values read as 1.
float finite_or_one(float v) {
    return std::isfinite(v) ? v : 1.0f;
}

}  // namespace

void weighted_shadow(ConstPlaneView s_n, ConstPlaneView u_n, PlaneView w) {
    check_same_size(s_n, u_n, "U_N");
    check_same_size(s_n, w, "W_N");
    const bool adjacent = s_n.pixel_stride == 1 && u_n.pixel_stride == 1 && w.pixel_stride == 1;
    parallel_for_rows(w.height, [&](int y) {
        if (adjacent)  // pointers to rows, so that the loop vectorises (the same values)
            return weighted_shadow_row(&s_n(0, y), &u_n(0, y), w.width, &w(0, y));
        for (int x = 0; x < w.width; ++x) {
            const float s = s_n(x, y), u = u_n(x, y);
            weighted_shadow_row(&s, &u, 1, &w(x, y));
        }
    });
}

void ratio_noise_estimate(ConstPlaneView w, int line_radius_px, std::uint32_t seed, PlaneView e) {
    check_same_size(w, e, "E");
    if (line_radius_px < 1) throw Error("ratio noise estimate: the line radius must be >= 1 pixel");
    const int width = w.width, height = w.height, radius = line_radius_px;
    // W_N with its edges repeated past the image, non-finite read as 1: every
    // tap is a plain load (taps beyond the edge repeat the edge).
    const int padded_width = width + 2 * radius + detail::kRatioNoiseRunPx;
    FramePlane<float> padded;
    padded.resize(std::size_t(padded_width) * std::size_t(height + 2 * radius));  // written in full
    parallel_for_rows(height + 2 * radius, [&](int row) {
        const int y = std::clamp(row - radius, 0, height - 1);
        float *__restrict to = &padded[std::size_t(row) * std::size_t(padded_width)];
        std::fill_n(to, radius, finite_or_one(w(0, y)));
        if (w.pixel_stride == 1) {  // a pointer to the row, so that the copy vectorises
            const float *__restrict from = &w(0, y);
            for (int x = 0; x < width; ++x) to[radius + x] = finite_or_one(from[x]);
        } else {
            for (int x = 0; x < width; ++x) to[radius + x] = finite_or_one(w(x, y));
        }
        std::fill(to + radius + width, to + padded_width, finite_or_one(w(width - 1, y)));
    });
    const float *interior = &padded[std::size_t(radius) * std::size_t(padded_width) + std::size_t(radius)];
    // Every line's taps of an inactive pixel lie in a constant window: E is 0 exactly, without the work.
    const FramePlane<unsigned char> along_rows =
        varying_along_rows(interior, std::size_t(padded_width), width, height, radius);
    detail::RatioNoiseSweep sweep;
    sweep.padded = padded.data();
    sweep.padded_row_floats = std::size_t(padded_width);
    sweep.width = width;
    sweep.height = height;
    sweep.line_radius_px = line_radius_px;
    sweep.seed = seed;
    FramePlane<float> raw;
    raw.resize(std::size_t(width) * std::size_t(height));  // written in full
    parallel_for_rows(height, [&](int y) {
        thread_local std::vector<unsigned char> active;
        active.resize(std::size_t(width));
        active_row(along_rows, width, height, radius, y, active.data());
        detail::ratio_noise_row(sweep, y, active.data(), &raw[std::size_t(y) * std::size_t(width)]);
    });
    // Sec. 4.2: E is noisy itself (random lines), so a 3x3 box filter over it.
    parallel_for_rows(height, [&](int y) {
        const float *rows[3];
        int row_count = 0;
        for (int ty = std::max(0, y - 1); ty <= std::min(height - 1, y + 1); ++ty)
            rows[row_count++] = &raw[std::size_t(ty) * std::size_t(width)];
        if (e.pixel_stride == 1) return detail::ratio_box_row(rows, row_count, width, &e(0, y));
        std::vector<float> out(static_cast<std::size_t>(width));
        detail::ratio_box_row(rows, row_count, width, out.data());
        for (int x = 0; x < width; ++x) e(x, y) = out[std::size_t(x)];
    });
}

}  // namespace aaf
