#pragma once

#include <cstdint>

#include "aaf/core/kernels/gather.h"

namespace aaf::detail {

/// The most channels one sweep of AAF's gather sums with the same weights.
inline constexpr int kMaxAafGatherChannels = 4;

/// One 1D sweep of AAF's separable gather (aaf_gather()): `channels`
/// sources in, as many outputs, planes of the guides' size, row-major; no
/// output aliases a source.
struct AafSweep {
    const GatherGuides *guides = nullptr;
    /// Along y, per pixel: aaf_uniform_reach_along_y(). (Along x the sweep
    /// compares each vector's span of taps itself.)
    const std::int32_t *uniform_reach = nullptr;
    float cos_threshold = 1.0f;
    bool symmetric_borders = false;
    bool along_y = false;  ///< false: along x
    int channels = 1;      ///< [1, kMaxAafGatherChannels]
    const float *source[kMaxAafGatherChannels] = {};
    float *output[kMaxAafGatherChannels] = {};
};

/// Gathers pixels [x_begin, x_end) of row `y` of `sweep` (AAF Eq. 10-12
/// along one axis, AAF Sec. 6's separable passes) with the widest SIMD
/// instruction set the CPU offers: neighbouring centre pixels in the lanes,
/// each summing its taps in order with every multiply and add rounded on its
/// own, so the bits are the same on every instruction set and thread count.
/// A tap weighs 2^(-log2(e) d^2 / (2 beta^2)) = exp(-d^2 / (2 beta^2))
/// (AAF Eq. 11), d its distance of AAF Eq. 12 (or slid along the light, as
/// GatherGuides documents), with a degree-4 polynomial for 2^f: relative
/// error below 3e-6, and exactly 1 at d = 0.
void aaf_gather_row(const AafSweep &sweep, int y, int x_begin, int x_end);

/// A run of equal pixels that meets the image's edge: any reach fits in it.
inline constexpr std::int32_t kUniformEndless = std::int32_t(1) << 30;

/// For columns [x_begin, x_end) of every row: how many pixels either side
/// along y have the pixel's object id and normal (then they pass the
/// gather's object and normal tests against it, which a sweep can skip),
/// kUniformEndless where that run meets the image's edge, -1 where the
/// pixel fails its own tests (a zero normal, a NaN id).
void aaf_uniform_reach_along_y(const GatherGuides &guides, float cos_threshold, int x_begin, int x_end,
                               std::int32_t *reach);

/// Name of the instruction set aaf_gather_row runs with now (Highway's
/// target name), for tests and benchmarks.
const char *aaf_gather_row_target();

}  // namespace aaf::detail
