#pragma once

#include <array>
#include <vector>

#include "aaf/core/contract/plane_view.h"

namespace aaf {

/// Viewing conditions and HDR settings of FLIP (Andersson et al., "FLIP: A
/// Difference Evaluator for Alternating Images", HPG 2020; HDR-FLIP,
/// Eurographics 2021).
struct FlipParams {
    /// Pixels per degree of visual angle. The default is the method's: a
    /// 3840-pixel-wide, 0.7 m wide monitor seen from 0.7 m,
    /// 0.7 * (3840 / 0.7) * pi / 180 = 67.02.
    float pixels_per_degree = 0.7f * (3840.0f / 0.7f) * 3.14159265f / 180.0f;
    /// HDR-FLIP exposures; 0 = the method's automatic choice,
    /// max(2, ceil(stop - start)) between the start and stop exposures.
    int exposures = 0;
};

/// Three planes of one RGB image.
using RgbPlanes = std::array<ConstPlaneView, 3>;

/// LDR-FLIP error map (row-major, values in [0, 1]) of two sRGB-encoded
/// images with values in [0, 1] (e.g. PNGs): colour pipeline (CSF filtering
/// in YCxCz, clamp to the RGB cube, Hunt-adjusted L*a*b*, HyAB, qc = 0.7,
/// redistribution with pc = 0.4, pt = 0.95) and feature pipeline (edges and
/// points on the normalised Y, w = 0.082 deg, qf = 0.5); error = dEc^(1 - dEf).
/// Borders replicate the edge pixels. Throws aaf::Error on mismatched sizes or
/// pixels per degree that are not positive and finite.
std::vector<float> ldr_flip(const RgbPlanes &reference, const RgbPlanes &test, const FlipParams &params = {});

/// HDR-FLIP error map of two linear HDR images: each is exposed by 2^e for
/// exposures e from start = log2(x_max / Y_max) to stop = log2(x_max /
/// Y_median) of the reference (x_max where the ACES curve reaches 0.85),
/// tone mapped with the ACES fit, clamped, sRGB encoded, and compared with
/// LDR-FLIP; the per-pixel maximum over exposures is the error. Negative
/// values are clipped to 0 first, as the method specifies.
std::vector<float> hdr_flip(const RgbPlanes &reference, const RgbPlanes &test, const FlipParams &params = {});

/// The pooled values FLIP reports for an error map: the mean and the
/// weighted median (about the value below which half of the total error
/// lies), by the rule of NVlabs/flip's Python tool: with the values sorted,
/// the first index i whose running sum reaches half the total, and the mean
/// of the values at i and i + 1 (the value at i when it is the last).
struct FlipSummary {
    double mean = 0;
    double weighted_median = 0;
};

/// Pools `errors` over the pixels where `selected` (same size) is non-zero;
/// an empty `selected` takes every pixel.
FlipSummary summarize_flip(const std::vector<float> &errors, const std::vector<unsigned char> &selected = {});

}  // namespace aaf
