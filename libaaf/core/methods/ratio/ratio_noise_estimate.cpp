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

/// 1 where the (2 radius + 1)^2 window around the pixel holds two different
/// values of `w`, else 0: a window with two values holds two neighbours that
/// differ, so it is enough to flag each pixel that differs from its right or
/// lower neighbour and dilate the flags by `radius` (a square, separably).
std::vector<unsigned char> varying_windows(ConstPlaneView w, int radius) {
    const int width = w.width, height = w.height;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    std::vector<unsigned char> flags(count, 0), rows(count, 0), out(count, 0);
    auto differ = [](float a, float b) { return !(a == b); };  // NaN differs from everything
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x)
            flags[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
                (x + 1 < width && differ(w(x, y), w(x + 1, y))) ||
                (y + 1 < height && differ(w(x, y), w(x, y + 1)));
    });
    parallel_for_rows(height, [&](int y) {
        const unsigned char *row = &flags[std::size_t(y) * std::size_t(width)];
        int last = -(1 << 30);  // the last flagged column seen
        for (int x = 0; x < std::min(width, radius); ++x)
            if (row[x]) last = x;
        for (int x = 0; x < width; ++x) {
            if (x + radius < width && row[x + radius]) last = x + radius;
            rows[std::size_t(y) * std::size_t(width) + std::size_t(x)] = last >= x - radius;
        }
    });
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            unsigned char any = 0;
            for (int ty = std::max(0, y - radius); ty <= std::min(height - 1, y + radius) && !any; ++ty)
                any = rows[std::size_t(ty) * std::size_t(width) + std::size_t(x)];
            out[std::size_t(y) * std::size_t(width) + std::size_t(x)] = any;
        }
    });
    return out;
}

}  // namespace

void weighted_shadow(ConstPlaneView s_n, ConstPlaneView u_n, PlaneView w) {
    check_same_size(s_n, u_n, "U_N");
    check_same_size(s_n, w, "W_N");
    parallel_for_rows(w.height, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            const float s = std::isfinite(s_n(x, y)) ? s_n(x, y) : 0.0f;
            const float u = std::isfinite(u_n(x, y)) ? u_n(x, y) : 0.0f;
            // ratio estimator Eq. 23; W_N = 1 where both are ~0 (Sec. 4.2).
            w(x, y) = u > 0 ? std::clamp(s / u, 0.0f, 1.0f) : 1.0f;
        }
    });
}

void ratio_noise_estimate(ConstPlaneView w, int line_radius_px, std::uint32_t seed, PlaneView e) {
    check_same_size(w, e, "E");
    if (line_radius_px < 1) throw Error("ratio noise estimate: the line radius must be >= 1 pixel");
    const int width = w.width, height = w.height;
    std::vector<float> raw(std::size_t(width) * std::size_t(height), 0.0f);
    // Every line's taps of an inactive pixel lie in a constant window: E is 0 exactly, without the work.
    const std::vector<unsigned char> active = varying_windows(w, line_radius_px);
    // The lines read W_N packed (a strided view is copied once).
    std::vector<float> packed;
    if (w.pixel_stride != 1 || w.row_stride != width) {
        packed.resize(raw.size());
        parallel_for_rows(height, [&](int y) {
            for (int x = 0; x < width; ++x)
                packed[std::size_t(y) * std::size_t(width) + std::size_t(x)] = w(x, y);
        });
    }
    detail::RatioNoiseSweep sweep;
    sweep.w = packed.empty() ? w.data : packed.data();
    sweep.width = width;
    sweep.height = height;
    sweep.line_radius_px = line_radius_px;
    sweep.seed = seed;
    sweep.active = active.data();
    parallel_for_rows(
        height, [&](int y) { detail::ratio_noise_row(sweep, y, &raw[std::size_t(y) * std::size_t(width)]); });
    // Sec. 4.2: E is noisy itself (random lines), so a 3x3 box filter over it.
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            float sum = 0.0f;
            int count = 0;
            for (int ty = std::max(0, y - 1); ty <= std::min(height - 1, y + 1); ++ty)
                for (int tx = std::max(0, x - 1); tx <= std::min(width - 1, x + 1); ++tx) {
                    sum += raw[std::size_t(ty) * std::size_t(width) + std::size_t(tx)];
                    ++count;
                }
            e(x, y) = sum / float(count);
        }
    });
}

}  // namespace aaf
