#pragma once

#include "aaf/core/kernels/light_bandlimit.h"
#include "aaf/core/methods/aaf/aaf_params.h"

namespace aaf {

/// The frequency analysis of AAF at one pixel. Frequencies are in 1/metres,
/// lengths in metres.
struct AafBandlimits {
    float s1 = 0;                 ///< max spectrum slope d1/d2min - 1 (AAF Eq. 4)
    float s2 = 0;                 ///< min spectrum slope d1/d2max - 1 (AAF Eq. 4)
    float omega_light = 0;        ///< Omega_L^max = 1/sigma
    float omega_x_max = 0;        ///< occlusion bandlimit along x (AAF Eq. 6)
    float omega_y_max = 0;        ///< occlusion bandlimit along y (AAF Eq. 7)
    float omega_x_f0 = 0;         ///< critical filter width (AAF Eq. 8)
    float omega_x_f = 0;          ///< mu * omega_x_f0 (Sec. 5.2)
    float beta_m = 0;             ///< spatial filter standard deviation (AAF Eq. 13)
    float samples_per_pixel = 0;  ///< n of AAF Eq. 15 with packing (a) of Fig. 4
};

/// Evaluates AAF Eq. 4-8, 13 and 15 at a pixel.
/// d1_m: receiver distance from the light plane; d2_min_m, d2_max_m: occluder
/// distances (0 < d2 <= d1); pixel_size_m: d of AAF Eq. 6; sigma_m: light sigma.
/// Slopes are clamped to >= 0 (an occluder measured beyond the receiver, which
/// curved geometry can produce, counts as contact). Where the min() of AAF Eq. 8
/// and Fig. 4(a) clip, the clipped value is used, so s2 -> 0 stays finite.
AafBandlimits aaf_bandlimits(float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m, float sigma_m,
                             const AafParams &params);

/// AAF at one pixel with one band-limit per light axis: AAF's 4D analysis
/// is a product of two 2D ones (x1, y1) and (x2, y2) (Sec. 4), so each axis
/// has its own AAF Eq. 8 and 13, and Eq. 15's rate is the product of the axes'
/// pixel and light factors. Equal sigmas give aaf_bandlimits() on both axes,
/// with the same rate.
struct AafAxisBandlimits {
    AafBandlimits u;  ///< along the light's axis_u
    AafBandlimits v;  ///< along the light's axis_v
    float samples_per_pixel = 0;
};
AafAxisBandlimits aaf_bandlimits_axes(float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m,
                                      LightBandlimitAxes sigma, const AafParams &params);

/// The sigmas AAF uses for `light` under params.light_bandlimit and params.light_axes.
LightBandlimitAxes aaf_light_sigmas_m(const LightPlane &light, const AafParams &params);

/// The mu (>= params.mu) at which the sampling rate of AAF Eq. 15 reaches
/// `samples`: n grows monotonically with mu, so bisection finds it to 1e-4
/// relative; returns params.mu when even that rate exceeds `samples`, and at
/// most 1e4 (a filter far below one pixel).
float mu_for_samples(float samples, float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m,
                     float sigma_m, const AafParams &params);
/// The same with the per-axis rate of aaf_bandlimits_axes().
float mu_for_samples(float samples, float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m,
                     LightBandlimitAxes sigma, const AafParams &params);

}  // namespace aaf
