#pragma once

#include "aaf/core/kernels/gather.h"

namespace aaf::detail {

/// The most channels one unmodulated sweep gathers with the same weights.
inline constexpr int kMaxGatherChannels = 4;

/// One unmodulated gather sweep (gather.cpp): `channels` sources in, as many
/// outputs, planes of the guides' size, row-major.
struct GatherSweep {
    const GatherGuides *guides = nullptr;
    float cos_threshold = 1.0f;
    bool symmetric_borders = false;
    bool along_x = true, along_y = false;
    int channels = 1;  ///< [1, kMaxGatherChannels]
    const float *source[kMaxGatherChannels] = {};
    float *output[kMaxGatherChannels] = {};
};

/// Gathers every pixel of row `y` of `sweep` (AAF Eq. 10-12, as gather()
/// documents) with the widest SIMD instruction set the CPU offers (Google
/// Highway's runtime dispatch). A sweep along x only (each pass of the
/// separable gather) puts neighbouring centre pixels in the lanes, each
/// summing its taps left to right; a 2D sweep puts a pixel's taps in 8
/// interleaved partial sums, added in order at the end. Either way the order
/// is fixed and multiplies and adds stay separate (no fused multiply-add), so
/// the bits are the same for every instruction set and thread count.
void gather_row(const GatherSweep &sweep, int y);

/// gather_row for pixels [x_begin, x_end) of row `y` alone (clamped to the
/// row), with the same bits: each pixel's sums depend on its taps only.
void gather_row(const GatherSweep &sweep, int y, int x_begin, int x_end);

/// Runs gather_row over the whole image in parallel. A vertical sweep of a
/// wide image goes in tiles of kGatherTileRows rows by kGatherStripPixels
/// columns, so that its window of rows (up to 2 radius + 1 of them, eight or
/// more planes) stays in the core's cache from one row to the next at any
/// image width; other sweeps go row by row.
void gather_rows_tiled(const GatherSweep &sweep);

inline constexpr int kGatherTileRows = 64;
inline constexpr int kGatherStripPixels = 256;

/// Name of the instruction set gather_row runs with now (Highway's target
/// name, e.g. "AVX2"), for tests and benchmarks.
const char *gather_row_target();

/// Whether that instruction set fuses the kernels' multiply-adds (one
/// rounding each: x86 AVX2 and AVX-512, Arm) or rounds the product first
/// (SSE4 and older): gather_exp_nonpositive's Fused (fast_exp.h). Targets
/// that agree on it give the same bits; the two kinds differ by rounding.
bool gather_row_fuses();

}  // namespace aaf::detail
