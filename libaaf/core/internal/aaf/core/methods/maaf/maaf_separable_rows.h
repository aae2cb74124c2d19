#pragma once

#include <cstddef>

#include "aaf/core/methods/maaf/maaf_accumulation.h"

namespace aaf::detail {

/// The complex terms of N = kMaafMaxPairs pairs: the central one, two per
/// component off one axis, two per pair of offset components (maaf_separable.cpp).
inline constexpr int kMaafMaxTerms =
    1 + 2 * (kMaafMaxPairs - 1) + 2 * (kMaafMaxPairs - 1) * (kMaafMaxPairs - 1);

/// Lines of centres are padded to a multiple of this many pixels (the
/// widest vector, AVX-512's 16 floats), so the kernels load whole vectors.
inline constexpr int kMaafLinePadding = 16;

/// What every line of one frame shares: the terms and the tap test.
struct MaafTerms {
    int pairs = 1;  ///< N used: components p = 0 .. pairs - 1 per axis
    int terms = 1;  ///< the complex terms (maaf_separable.cpp's terms_for)
    const int *pu = nullptr, *pv = nullptr;
    const float *sign_v = nullptr;  ///< +1: e^{j (a + b)}, -1: e^{j (a - b)}
    float cos_threshold = 1.0f;     ///< taps whose normals turn further are rejected
};

/// One line (an image row, or an image column for the vertical pass) of
/// `count` centres, count a multiple of kMaafLinePadding, and its taps: the
/// taps of centre i at offset o are at margin + i + o of the tap arrays,
/// margin at least the largest reach; taps outside the image have object id NaN.
struct MaafLine {
    int count = 0, margin = 0;
    /// The taps' guides: coordinates along the light's axes (metres), unit
    /// normal x, y, z, object id; guide k at guides + k * guide_stride.
    const float *guides = nullptr;
    std::size_t guide_stride = 0;
    /// The centres' kernels, centre i at i: 1 / (2 s_p^2) (m^-2, `pairs`
    /// arrays), C_x^p (rad/m, `pairs`), reach radius_p (pixels, `pairs`, 0
    /// where not filtered), then the largest reach; array k at kernels + k * kernel_stride.
    const float *kernels = nullptr;
    std::size_t kernel_stride = 0;
    /// The taps' complex sources (4 * terms arrays: value re, value im,
    /// unoccluded re, unoccluded im) or, for the real pass, the same.
    const float *sources = nullptr;
    std::size_t source_stride = 0;
    /// Centre i's output q at out + i * out_centre_step + q * out_plane_step.
    float *out = nullptr;
    std::size_t out_centre_step = 1, out_plane_step = 0;
};

/// One pass of the separable MAAF filter over a line: for each centre, with
/// its own kernels, the sum over the taps within its reach that gather()
/// accepts (the centre always; else the same object and a normal within the
/// threshold) of each term's weight g_p(du) g_q(dv) e^{j (C_x^p du +
/// sign_v C_x^q dv)} (MAAF Eq. 12, 13) times its complex sources. `complex`:
/// all 4 * terms outputs (the vertical pass; a centre whose largest reach is
/// 0 keeps its sources); else the real parts of the value and unoccluded
/// terms, 2 * terms outputs (the horizontal pass). Taps are summed in order
/// of offset, every multiply and add rounded on its own, so every
/// instruction set and lane count gives the same bits.
void maaf_line_pass(const MaafTerms &terms, const MaafLine &line, bool complex);

}  // namespace aaf::detail
