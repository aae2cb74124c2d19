#pragma once

#include "aaf/core/contract/plane_view.h"

namespace aaf {

/// Baseline denoiser: a separable screen-space Gaussian of one width for the
/// whole image (the "non-adaptive filter" of AAF Fig. 6 and 10), cut at
/// 3 sigma and renormalised at the borders. `sigma_px` in pixels; 0 copies.
/// `input` and `output` must not alias. Runs on the current oneTBB arena.
void fixed_gaussian_filter(ConstPlaneView input, float sigma_px, PlaneView output);

}  // namespace aaf
