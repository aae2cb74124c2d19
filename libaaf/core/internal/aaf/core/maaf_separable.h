#pragma once

#include <array>
#include <vector>

#include "aaf/core/gather.h"

namespace aaf {

/// One complex-modulated Gaussian per pixel for maaf_separable_gather(): the
/// tap weight exp(-(du^2 inv_u + dv^2 inv_v)) e^{j (omega_u du + omega_v dv)},
/// du and dv the tap's displacement from the centre along the guides' two
/// axes (metres), reaching radius_px pixels along each image axis (0 = the
/// pixel keeps its value). Row-major, the guides' size.
struct ComplexKernels {
    std::vector<float> omega_u, omega_v;  ///< rad/m
    std::vector<float> inv_u, inv_v;      ///< 1 / (2 sigma^2), m^-2
    std::vector<int> radius_px;
};

/// A complex source for maaf_separable_gather(): real and imaginary planes, row-major.
struct ComplexPlane {
    std::vector<double> re, im;
};

/// MAAF's x-side filtering of complex sources (MAAF Eq. 21 with the pair of
/// Eq. 12 kept as one complex exponential, whose phase is linear in the
/// displacement and so splits exactly over two 1D passes): a vertical pass
/// with each intermediate pixel's kernel, then a horizontal pass with each
/// centre's, as AAF Sec. 6 separates its Gaussian (exact where the kernel is
/// locally constant and image rows and columns map to the light's two axes).
/// Unnormalised sums; taps are rejected as gather() rejects them (another
/// object, a normal beyond the threshold; the centre always counts). Runs on
/// the current oneTBB arena in a fixed order: thread-count independent.
/// `sources` and the returned planes are in the same order.
std::vector<ComplexPlane> maaf_separable_gather(const GatherGuides &guides, float normal_threshold_deg,
                                                const ComplexKernels &kernels,
                                                const std::vector<ComplexPlane> &sources);

}  // namespace aaf
