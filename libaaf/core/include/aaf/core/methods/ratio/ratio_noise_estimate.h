#pragma once

#include <cstdint>

#include "aaf/core/contract/plane_view.h"

namespace aaf {

/// The stochastic illumination-weighted shadow W_N = S_N / U_N
/// (ratio estimator Eq. 23) of one channel (or of the luminance), written to `w`:
/// in [0, 1]; 1 where U_N is not above 0 (both ~0, ratio estimator Sec. 4.2's
/// convention for ratio estimator Eq. 29); non-finite inputs read as 0. All views one size.
void weighted_shadow(ConstPlaneView s_n, ConstPlaneView u_n, PlaneView w);

/// The noise estimate E of ratio estimator Eq. 29 at every pixel of `w` (a
/// W_N image): along 4 lines through the pixel, 45 degrees apart and turned
/// by a per-pixel angle in [0, 45) degrees hashed from (x, y, seed), the sum
/// of |W(t-1) - 2 W(t) + W(t+1)| over the line's 2 line_radius_px + 1 taps
/// (nearest pixel, clamped at the image edge), divided by the 2 line_radius_px - 1
/// second differences so that E (per pixel) does not depend on the line's
/// length; the mean over the lines, then a 3x3 box filter (Sec. 4.2). E = 0 on
/// a constant W, near 1 for independent fair coin flips (nearest-pixel taps of a
/// diagonal line sometimes repeat a pixel), at most 2 / (2 line_radius_px - 1)
/// on a line crossing one unit step. `e` must not alias `w`; line_radius_px >= 1.
/// Deterministic, any thread count. Throws aaf::Error on mismatched sizes.
void ratio_noise_estimate(ConstPlaneView w, int line_radius_px, std::uint32_t seed, PlaneView e);

}  // namespace aaf
