#pragma once

#include <cstddef>

namespace aaf::detail {

/// Rows of centres are padded to a multiple of this many pixels (the widest
/// vector, AVX-512's 16 floats), so the kernel loads whole vectors.
inline constexpr int kMaaf6RowPadding = 16;

/// Channels per axis of the N = 3 layer (2N - 1): the kernel's channel layout.
inline constexpr int kMaaf6Functions = 5;

/// One centre's filter, as maaf6_filter.cpp's PixelFilter: a row of
/// centres holds field f of centre x at params[f * stride + x].
enum Maaf6CentreField : int {
    kCentrePx,
    kCentrePy,
    kCentrePz,
    kCentreNx,
    kCentreNy,
    kCentreNz,
    kCentreT1x,
    kCentreT1y,
    kCentreT1z,
    kCentreT2x,
    kCentreT2y,
    kCentreT2z,
    /// sigma_x^p / k of components p = 0, 1, 2 (the envelope is exp(-(dx sigma_x^p / k)^2 / 2));
    /// that of p = 0 is also 1 / the central std for the off-plane weight
    kCentreScale0,
    kCentreScale1,
    kCentreScale2,
    kCentreOmega1,  ///< C_x^p of p = 1, 2, rad/m
    kCentreOmega2,
    kCentreGain1,  ///< 2 mu_p of p = 1, 2 (0: the central filter alone)
    kCentreGain2,
    kCentreDc1,  ///< e_p, the pairs' DC corrections
    kCentreDc2,
    kCentreLensScale,    ///< 1 / the lens band's std, 0 without a lens filter
    kCentreAxisScale,    ///< sigma_x / k of the axis-aligned filter beside the partition
    kCentreScalePixels,  ///< pixel size times kCentreScale0: 1 / the central std in pixels
    kCentreRadius,       ///< the window's radius, pixels; -1: not filtered (no taps)
    kCentreAxisRadius,   ///< the axis-aligned filter's window radius, pixels; -1: none (no partition)
    kCentreFieldCount,
};

/// What a centre's taps sum to (maaf6_filter.cpp's TapSums): sums field f of
/// centre x at sums[f * stride + x].
enum Maaf6SumField : int {
    kSumNumR,
    kSumNumG,
    kSumNumB,
    kSumDen,
    kSumNum0R,
    kSumNum0G,
    kSumNum0B,
    kSumDen0,
    kSumNum1R,
    kSumNum1G,
    kSumNum1B,
    kSumDen1,
    kSumUnoccluded,
    kSumUnoccludedDen,
    kSumMassKept,
    kSumFieldCount,
};

/// The frame's taps: planes of width x height floats, row by row.
struct Maaf6Taps {
    int width = 0, height = 0;
    std::ptrdiff_t row_stride = 0;  ///< every plane's, in floats
    /// Position (metres) and unit normal; a tap that can never be used (the
    /// background, no samples, no normal) has normal x NaN.
    const float *px = nullptr, *py = nullptr, *pz = nullptr;
    const float *nx = nullptr, *ny = nullptr, *nz = nullptr;
    const float *inv_samples = nullptr;  ///< 1 / the tap's samples
    /// The layer's sums (channel c's R, G, B at 3 c .. 3 c + 2) and weights,
    /// (2N - 1)^2 = 25 channels, c = a 5 + b.
    const float *const *sums = nullptr;
    const float *const *weights = nullptr;
    float cos_threshold = 1.0f;  ///< taps whose normals turn further are rejected
};

/// The tap sums of row y's `count` centres (count a multiple of
/// kMaaf6RowPadding; centres past the image have radius -1), each with its
/// own filter (`params`, Maaf6CentreField) into `sums` (Maaf6SumField), both
/// with `stride` >= count. Per centre the taps of its window inside the image
/// in row-major order, those accepted as maaf6_filter.cpp's tap_accepted()
/// accepts them, weighted as its add_tap() weighs them, in float with
/// Highway's polynomial exp and sin/cos, one centre per lane, every multiply
/// and add rounded on its own: the same bits on every instruction set and
/// for any thread count.
void maaf6_row_sums(const Maaf6Taps &taps, int y, int count, const float *params, std::size_t stride,
                    float *sums);

}  // namespace aaf::detail
