#pragma once

#include <cstddef>
#include <cstdint>

#include "aaf/core/util/frame_allocator.h"

namespace aaf::detail {

/// The most planes one bilateral pass filters (the ratio estimator filters 6: S_N and U_N RGB).
inline constexpr int kRatioMaxPlanes = 8;

/// Floats after the last pixel of every plane the vertical pass reads (the
/// widest vector of floats): a vector at a row's end stays in the allocation.
inline constexpr std::size_t kRatioPlaneSlack = 16;

/// The joint bilateral's per-pixel guides (ratio_bilateral.cpp fills them),
/// planar, row-major, each vector kRatioPlaneSlack floats longer than the image.
struct RatioBilateralPlanes {
    int width = 0, height = 0;
    FramePlane<float> px, py, pz;  ///< the position, metres
    /// 1 / (plane_sigma scale_m); 0 marks no surface: never a tap, never filtered.
    FramePlane<float> inv_scale;
    /// ceil(cutoff x sigma) (at most the image's larger side): how far the
    /// taps reach; 0 keeps the pixel's value.
    FramePlane<std::int32_t> radius_px;
};

/// One row of the guides and widths RatioBilateralPlanes is made from, packed.
struct RatioGuideRow {
    const float *position[3], *normal[3];
    const float *scale_m;   ///< the world length a pixel covers, metres
    const float *sigma_px;  ///< the bilateral's sigma
    float plane_sigma = 1, cutoff_sigmas = 3;
};

/// Writes row `y` of every plane of `planes` (sized already) from `in`: the
/// position and 1 / (plane_sigma scale_m) where the pixel is a surface
/// (positive finite scale, finite position, non-zero finite normal), zeros
/// elsewhere; the reach 0 where sigma is not positive and finite.
void ratio_planes_row(const RatioGuideRow &in, int y, RatioBilateralPlanes &planes);

/// One pass of the bilateral over `count` planes with the same weights.
struct RatioBilateralSweep {
    const RatioBilateralPlanes *planes = nullptr;
    int count = 1;  ///< [1, kRatioMaxPlanes]
    /// The vertical pass's sources: guide-sized row-major planes, kRatioPlaneSlack floats after the last.
    const float *source[kRatioMaxPlanes] = {};
    float *output[kRatioMaxPlanes] = {};  ///< the horizontal pass's, guide-sized
};

/// The horizontal pass over row `y`: output[k](x, y) = the weighted mean of
/// source_rows[k][x'] over the row's taps x' of pixel x, for every x;
/// `centres` points at the row's guides (the filtered pixels' tangent planes
/// and Gaussians are computed from them, not kept as frame planes).
void ratio_bilateral_row_x(const RatioBilateralSweep &sweep, int y, const float *const *source_rows,
                           const RatioGuideRow &centres);

/// The vertical pass over pixels [x_begin, x_end) of row `y`: their `count`
/// filtered values plane after plane to `values` (count x (x_end - x_begin) floats);
/// `centres` points at those pixels' guides.
void ratio_bilateral_row_y(const RatioBilateralSweep &sweep, int y, int x_begin, int x_end, float *values,
                           const RatioGuideRow &centres);

/// RatioComposition::compose() of the ratio estimator over `count` adjacent
/// pixels: rgb[x] (+)= u[x] W, W = clamp(s_den[x] / u_den[x], 0, 1) where
/// u_den[x] > 0, else 1 (ratio estimator Eq. 25, times U); `rgb` overlaps
/// none of the inputs.
void ratio_compose_row(const float *u, const float *s_den, const float *u_den, int count, bool accumulate,
                       float *rgb);

/// A hash (PCG-style integer mix) in [0, 1) of (x, y, seed), so the noise
/// estimate's turn depends only on the place and the seed, never on the
/// thread count.
inline float ratio_pixel_random(int x, int y, std::uint32_t seed) {
    std::uint32_t h = std::uint32_t(x) * 0x8da6b343u ^ std::uint32_t(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return float(h >> 8) * (1.0f / 16777216.0f);
}

/// Pixels of a row that share one turn of the noise estimate's lines (x /
/// kRatioNoiseRunPx is hashed): their taps lie at the same offsets, so they
/// are read with one vector load per tap instead of a gather. A constant,
/// not the vector width: every instruction set turns the same lines.
inline constexpr int kRatioNoiseRunPx = 8;

/// The noise estimate's lines over W_N (ratio_noise_estimate.cpp).
struct RatioNoiseSweep {
    /// W_N with non-finite values read as 1, its rows and columns
    /// repeated past the edges: `line_radius_px` rows above and below,
    /// `line_radius_px` columns left, line_radius_px + kRatioNoiseRunPx right.
    const float *padded = nullptr;
    std::size_t padded_row_floats = 0;  ///< floats from one padded row to the next
    int width = 0, height = 0;
    int line_radius_px = 1;
    std::uint32_t seed = 0;
};

/// Row `y` of E before its box filter (ratio estimator Eq. 29, the mean over 4 lines) to `raw` (width
/// floats); `active` (width bytes) is 0 where every line's taps are equal: E = 0 there.
void ratio_noise_row(const RatioNoiseSweep &sweep, int y, const unsigned char *active, float *raw);

/// One row of a 3x3 box filter clipped to the image: out[x] = the mean of
/// rows[r][x - 1 .. x + 1] (clipped to [0, width)) over the `row_count`
/// rows (1 to 3, top to bottom), summed in reading order from 0.
void ratio_box_row(const float *const *rows, int row_count, int width, float *out);

}  // namespace aaf::detail
