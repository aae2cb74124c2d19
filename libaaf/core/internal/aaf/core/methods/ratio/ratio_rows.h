#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

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
    std::vector<float> px, py, pz;  ///< the position, metres
    std::vector<float> nx, ny, nz;  ///< the unit normal
    std::vector<float> plane_m;     ///< n . p: the tangent plane's offset, metres
    /// 1 / (plane_sigma scale_m); 0 marks no surface: never a tap, never filtered.
    std::vector<float> inv_scale;
    std::vector<float> minus_half_inv_sigma_sq;  ///< -1 / (2 sigma^2), sigma in pixels
    /// ceil(cutoff x sigma): how far the taps reach; 0 keeps the pixel's value.
    std::vector<std::int32_t> radius_px;
};

/// One pass of the bilateral over `count` planes with the same weights.
struct RatioBilateralSweep {
    const RatioBilateralPlanes *planes = nullptr;
    int count = 1;  ///< [1, kRatioMaxPlanes]
    /// Guide-sized row-major planes; those of the vertical pass with kRatioPlaneSlack floats after them.
    const float *source[kRatioMaxPlanes] = {};
    float *output[kRatioMaxPlanes] = {};  ///< the horizontal pass's, guide-sized
};

/// The horizontal pass over row `y`: output[k](x, y) = the weighted mean of
/// source[k] over the row's taps of pixel x, for every x.
void ratio_bilateral_row_x(const RatioBilateralSweep &sweep, int y);

/// The vertical pass over pixels [x_begin, x_end) of row `y`: their `count`
/// filtered values pixel after pixel to `values` ((x_end - x_begin) x count floats).
void ratio_bilateral_row_y(const RatioBilateralSweep &sweep, int y, int x_begin, int x_end, float *values);

/// A per-pixel hash (PCG-style integer mix) in [0, 1), so the noise
/// estimate's turn depends only on the pixel and the seed, never on the
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

/// The noise estimate's lines over W_N (ratio_noise_estimate.cpp).
struct RatioNoiseSweep {
    const float *w = nullptr;  ///< W_N, row-major
    int width = 0, height = 0;
    int line_radius_px = 1;
    std::uint32_t seed = 0;
    const unsigned char *active = nullptr;  ///< 0 where every line's taps are equal: E = 0
};

/// Row `y` of E before its box filter (ratio estimator Eq. 29, the mean over 4 lines) to `raw` (width
/// floats).
void ratio_noise_row(const RatioNoiseSweep &sweep, int y, float *raw);

}  // namespace aaf::detail
