#pragma once

#include "aaf/core/methods/maaf/maaf_accumulation.h"

namespace aaf::detail {

/// The complex terms of N = kMaafMaxPairs pairs: the central one, two per
/// component off one axis, two per pair of offset components (maaf_separable.cpp).
inline constexpr int kMaafMaxTerms =
    1 + 2 * (kMaafMaxPairs - 1) + 2 * (kMaafMaxPairs - 1) * (kMaafMaxPairs - 1);

/// Row storage of maaf_separable_filter()'s planes is padded to a multiple
/// of this many pixels (the widest vector, AVX-512's 16 floats), so that the
/// row kernels load whole vectors of centres without a scalar tail.
inline constexpr int kMaafRowPadding = 16;

/// One frame's inputs to the separable MAAF passes, planar: plane q of a
/// per-pixel quantity starts at q * stride * height, pixel (x, y) at
/// y * stride + x. Padding columns hold object id NaN (never a tap) and radii 0.
struct MaafSeparableFrame {
    int width = 0, height = 0, stride = 0;
    int pairs = 1;  ///< N used: components p = 0 .. pairs - 1 per axis
    int terms = 1;  ///< the complex terms (maaf_separable.cpp's terms_for)
    const int *term_pu = nullptr, *term_pv = nullptr;
    const float *term_sign_v = nullptr;  ///< +1: e^{j (a + b)}, -1: e^{j (a - b)}
    float cos_threshold = 1.0f;          ///< taps whose normals turn further are rejected
    /// Guides: signed coordinates along the light's axes (metres), unit normals, object ids.
    const float *coord_u = nullptr, *coord_v = nullptr;
    const float *normal_x = nullptr, *normal_y = nullptr, *normal_z = nullptr, *object_id = nullptr;
    /// Kernels, `pairs` planes each: 1 / (2 s_p^2) (m^-2), C_x^p (rad/m), reach in pixels (0: not filtered).
    const float *inv_two_sigma_sq = nullptr, *omega = nullptr, *radius_px = nullptr;
    const float *widest_px = nullptr;  ///< per pixel, the largest of its terms' reaches
    /// 4 * terms planes: value re, value im, unoccluded re, unoccluded im, each `terms` planes.
    const float *sources = nullptr;
};

/// One row of intermediates or guides of the horizontal pass: `count` pixels
/// with `margin` pixels of padding each side, pixel x at margin + x.
struct MaafPaddedRow {
    int margin = 0, length = 0;
};

/// The vertical pass of row y: for each centre x of the row, with its own
/// kernels, the sum over the taps (x, ty), |ty - y| <= its reach, that
/// gather() accepts (the centre always; else the same object and a normal
/// within the threshold) of each term's weight g_p(du) g_q(dv)
/// e^{j (C_x^p du + sign_v C_x^q dv)} times its complex sources (MAAF Eq.
/// 12, 13), into out[q * row.length + row.margin + x], q over the 4 * terms
/// planes of MaafSeparableFrame::sources. A centre whose widest reach is 0
/// keeps its sources. Taps are summed in order of ty, every multiply and add
/// rounded on its own, so every instruction set and lane count gives the
/// same bits.
void maaf_vertical_row(const MaafSeparableFrame &frame, int y, float *out, MaafPaddedRow row);

/// The horizontal pass of row y over the vertical pass's output `in` (as
/// maaf_vertical_row writes it), with each centre's kernels and the row's
/// guides padded likewise (`guides`: coord_u, coord_v, normal x, y, z,
/// object id, six rows of row.length; object id NaN in the margins): the
/// real parts of each term's filtered value and unoccluded sources into the
/// row's sums[j * frame.stride + x] and sums[(terms + j) * frame.stride + x].
/// Taps in order of tx; the same bits on every instruction set.
void maaf_horizontal_row(const MaafSeparableFrame &frame, int y, const float *in, const float *guides,
                         MaafPaddedRow row, float *sums);

}  // namespace aaf::detail
