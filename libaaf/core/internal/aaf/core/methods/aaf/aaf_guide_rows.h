#pragma once

#include <cstddef>

namespace aaf::detail {

/// What aaf_gather_guides() computes once per image and uses at every pixel.
struct AafGuideConstants {
    /// The light's plane (LightPlane): centre, tangent axes, normal.
    float center[3] = {}, axis_u[3] = {}, axis_v[3] = {}, light_normal[3] = {};
    float variance_u_m2 = 0, variance_v_m2 = 0;  ///< LightPlane::variance_u_m2/_v_m2
    float sigma_u_m = 0, sigma_v_m = 0;          ///< aaf_light_sigmas_m()
    /// AafParams: mu (the floor where it is bisected per pixel), k, alpha,
    /// fixed_beta_m, max_radius_px.
    float mu = 2, k = 3, alpha = 1, fixed_beta_m = 0, max_radius_px = 64;
    float cutoff_sigmas = 3;       ///< taps reach ceil(cutoff_sigmas beta / pixel size) pixels
    bool projected_pixel = false;  ///< AafParams::projected_pixel
    bool along_light = false;      ///< light_distance is not OrthogonalProjection: the shear planes
    bool guarded = false;          ///< light_distance is Guarded
    bool anisotropic = false;      ///< sigma_u_m != sigma_v_m: the inv_two_sigma_sq_v plane
    bool per_pixel_mu = false;     ///< mu_for_samples() per pixel from `spp` (AAF Sec. 5.2)
};

/// One row of aaf_gather_guides()' inputs, `count` contiguous pixels each;
/// d2 are the occluder fill's (occluder_fill.h). `spp` only with per_pixel_mu.
struct AafGuideRowInputs {
    const float *position[3] = {}, *normal[3] = {};
    const float *object_id = nullptr, *d1_m = nullptr, *pixel_size_m = nullptr;
    const float *d2_min_m = nullptr, *d2_max_m = nullptr, *spp = nullptr;
};

/// Where the row's guides (GatherGuides' planes) and beta go, `count`
/// contiguous pixels each. inv_two_sigma_sq_v only when anisotropic, the
/// four shear planes only when along_light, beta_m where wanted (nullptr:
/// not written); the others always.
struct AafGuideRowOutputs {
    float *coord_u_m = nullptr, *coord_v_m = nullptr, *normal[3] = {}, *object_id = nullptr;
    float *inv_two_sigma_sq = nullptr, *inv_two_sigma_sq_v = nullptr;
    float *coord_n_m = nullptr, *shear_u = nullptr, *shear_v = nullptr, *inv_two_sigma_sq_n = nullptr;
    float *beta_m = nullptr;
    int *radius_px = nullptr;
};

/// aaf_gather_guides()' per-pixel step over `count` pixels of one row:
/// the light-plane coordinates and shear (AAF Eq. 12), the unit normal,
/// AAF Eq. 4-8 and 13 (with mu_for_samples()' bisection of Eq. 15 per pixel,
/// all lanes stepping together), the filter's reach and 1 / (2 beta^2).
/// Every output is written. Neighbouring pixels in the SIMD lanes (Google
/// Highway's runtime dispatch), each lane doing the scalar definitions'
/// (aaf_bandlimits.h) operations in their order with no fused multiply-add,
/// so every instruction set gives their bits.
void aaf_guide_row(const AafGuideConstants &constants, const AafGuideRowInputs &in,
                   const AafGuideRowOutputs &out, int count);

/// Name of the instruction set aaf_guide_row runs with now, for tests.
const char *aaf_guide_row_target();

}  // namespace aaf::detail
