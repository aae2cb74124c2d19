#pragma once

#include <vector>

#include "aaf/core/kernels/gather.h"
#include "aaf/core/methods/maaf/maaf_accumulation.h"

namespace aaf {

/// One pixel's x-side kernels for maaf_separable_filter(), per component
/// p = 0 .. N-1 (p >= 0 of a pair; maaf_components.h).
struct MaafPixelKernel {
    bool filtered = false;                       ///< false: the pixel keeps its value (and is a plain tap)
    float omega_x[kMaafMaxPairs] = {};           ///< C_x^p, rad/m
    float inv_two_sigma_sq[kMaafMaxPairs] = {};  ///< 1 / (2 s^2) of the primal Gaussian of std s, m^-2
    int radius_px[kMaafMaxPairs] = {};           ///< 3 primal standard deviations, capped; pixels
    double weight[kMaafMaxPairs] = {};           ///< mu_0 sigma_x^0, 2 mu_p sigma_x^p (MAAF Eq. 21)
};

/// What maaf_separable_filter() returns per pixel (row-major): the filtered
/// value and unoccluded sums over all component pairs (MAAF Eq. 21, weights
/// included), and the central pair's (p = q = 0, AAF's filter) alone.
struct MaafFilteredSums {
    std::vector<double> numerator, denominator;
    std::vector<double> central_numerator, central_denominator;
};

/// MAAF's x-side filtering of the (2N - 1)^2 channels of value and
/// unoccluded sums (maaf_accumulation.h's layout; `pairs` = N used, at most
/// the sums' `sum_pairs`) with each pixel's kernels: for every pair of
/// components (p along the light's first axis, q along its second) the
/// channels are regrouped into complex sources whose kernels
/// g_p(du) g_q(dv) e^{j (C_x^p du +- C_x^q dv)} are separable (MAAF Eq. 13
/// with the cos/sin pair of MAAF Eq. 12 kept as one complex exponential), then
/// filtered by a vertical pass with each intermediate pixel's kernel and a
/// horizontal pass with each centre's, as AAF Sec. 6 separates its Gaussian
/// (exact where the kernel is locally constant and image rows and columns
/// map to the light's two axes). du, dv: the tap's signed displacement from
/// the centre along the light's two tangent axes (the guides' coordinates,
/// metres). A pair's taps reach max(radius_p, radius_q) pixels along each
/// pass (a square window, as the full-window filter); taps are rejected as
/// gather() rejects them (another object, a normal beyond the threshold;
/// the centre always counts). Both passes run in maaf_line_pass() (one
/// centre per vector lane, maaf_separable_rows.h): each tap's Gaussians and
/// phase factors e^{j C_x^p du} (a polynomial sin/cos, not a recurrence:
/// du is not linear in the pixel offset) are computed once and shared by
/// every term, in float, unfused; each pixel's sums run in a fixed order,
/// so the result depends neither on the thread count nor on the
/// instruction set. Runs on the current oneTBB arena.
MaafFilteredSums maaf_separable_filter(const GatherGuides &guides, float normal_threshold_deg,
                                       const std::vector<MaafPixelKernel> &kernels, int sum_pairs, int pairs,
                                       const std::vector<std::vector<float>> &value_sums,
                                       const std::vector<std::vector<float>> &unoccluded_sums);

}  // namespace aaf
