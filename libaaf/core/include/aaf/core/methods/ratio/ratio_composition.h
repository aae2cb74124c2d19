#pragma once

#include <array>
#include <vector>

#include "aaf/core/contract/plane_view.h"
#include "aaf/core/util/frame_allocator.h"

namespace aaf {

/// Which estimate of the shadowed direct light is denoised (ratio estimator Sec. 3).
enum class RatioEstimator {
    Ratio,           ///< U x den(S_N) / den(U_N) (ratio estimator Eq. 25 applied to Eq. 15)
    Stochastic,      ///< den(S_N), the full-stochastic estimate (ratio estimator Eq. 10)
    ControlVariate,  ///< den(U - U_N + S_N), the control variate with c = 1 (ratio estimator Eq. 11)
};

/// One light's (or the summed) layers of the ratio contract, views of one
/// size. The luminance views are read only by the grey ratio estimator.
struct RatioLayers {
    std::array<ConstPlaneView, 3> analytic;    ///< U (ratio estimator Eq. 20), RGB
    std::array<ConstPlaneView, 3> shadowed;    ///< S_N (ratio estimator Eq. 21, as a mean), RGB
    std::array<ConstPlaneView, 3> unshadowed;  ///< U_N (ratio estimator Eq. 22, as a mean), RGB
    ConstPlaneView shadowed_y, unshadowed_y;   ///< luminance of S_N and U_N (Sec. 3.4)
};

/// W = den(S_N) / den(U_N) clamped to [0, 1] (the denoised ratio of the same
/// weights stays a weighted mean of visibilities, ratio estimator Eq. 14); 1 where den(U_N)
/// is not above 0: no sample of any tap saw light, and the pixel is then
/// shown unshadowed, as ratio estimator Eq. 29's convention W_N = 1 for S_N = U_N = 0 (a
/// pixel whose U is ~0 stays ~0). Never NaN for finite inputs.
inline float ratio_weight(float denoised_s, float denoised_u) {
    if (!(denoised_u > 0)) return 1.0f;
    const float w = denoised_s / denoised_u;
    return w < 0 ? 0.0f : (w > 1 ? 1.0f : w);
}

/// How an estimator's denoised planes become radiance.
class RatioComposition {
  public:
    RatioComposition(const RatioLayers &layers, RatioEstimator estimator, bool grey);

    /// The planes the denoiser filters, all with the same weights, non-finite
    /// values read as 0: Ratio: S_N R,G,B then U_N R,G,B (grey: S_N Y, U_N Y);
    /// Stochastic: S_N R,G,B; ControlVariate: U - U_N + S_N, R,G,B.
    std::vector<FramePlane<float>> sources() const;
    /// How many planes sources() returns.
    int plane_count() const;

    /// Pixel (x, y)'s radiance from its denoised planes (`denoised` holds
    /// plane_count() values in sources()' order), added to `rgb` when
    /// `accumulate`, else written there.
    void compose(int x, int y, const float *denoised, float *rgb, bool accumulate) const {
        float out[3] = {0, 0, 0};
        switch (estimator_) {
            case RatioEstimator::Ratio:
                for (int c = 0; c < 3; ++c) {
                    const float w = grey_ ? ratio_weight(denoised[0], denoised[1])
                                          : ratio_weight(denoised[c], denoised[3 + c]);
                    const float u = layers_.analytic[c](x, y);
                    out[c] = u * w;  // ratio estimator Eq. 25, times U (Eq. 24)
                }
                break;
            case RatioEstimator::Stochastic:
            case RatioEstimator::ControlVariate:
                for (int c = 0; c < 3; ++c) out[c] = denoised[c];
                break;
        }
        for (int c = 0; c < 3; ++c) rgb[c] = accumulate ? rgb[c] + out[c] : out[c];
    }

    /// compose() over pixels [x_begin, x_end) of row `y` into `rgb`, denoised[k]
    /// the pixels' plane k (x_end - x_begin values each); the same values.
    /// `rgb` overlaps neither the layers nor `denoised`.
    void compose_row(int y, int x_begin, int x_end, const float *const *denoised,
                     const std::array<PlaneView, 3> &rgb, bool accumulate) const;

  private:
    RatioLayers layers_;
    RatioEstimator estimator_;
    bool grey_;
};

}  // namespace aaf
