#pragma once

#include <array>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/light_plane.h"
#include "aaf/core/contract/plane_view.h"
#include "aaf/core/methods/aaf/aaf_params.h"

namespace aaf {

/// First-pass AOVs the sampling plan reads (see aov_contract.h), one size.
struct SamplingPlanInputs {
    ConstPlaneView d1;
    ConstPlaneView d2_min;
    ConstPlaneView d2_max;
    ConstPlaneView object_id;
    ConstPlaneView pixel_size;
    /// Optional (all three or none): the receiver's normal, for the projected
    /// pixel footprint (AafParams::projected_pixel); without it the plan uses
    /// the receiver's footprint.
    std::array<ConstPlaneView, 3> normal;
};

struct SamplingPlanParams {
    int first_pass_spp = 9;  ///< samples already taken everywhere (AAF Sec. 6: 9, stratified)
    int max_spp = 100;       ///< cap on the total per pixel
};

/// AAF's adaptive sampling rate (Sec. 5.1, 6): for every pixel the total
/// light samples n of AAF Eq. 15 (packing (a) of Fig. 4, A_p = pixel_size^2,
/// A_l = (2 sigma)^2; AAF Eq. 21 when nothing clips), with sigma the light's
/// band-limit sigma under aaf.light_bandlimit (the filter's), rounded up and clamped to
/// [first_pass_spp, max_spp]. Unoccluded pixels first borrow occluder
/// distances within `aaf.fill_radius_px` (Sec. 6); with none, or on the
/// background, n = first_pass_spp. Uses aaf.mu and aaf.alpha. Writes totals
/// (not the remainder) into `spp_out`. Runs on the current oneTBB arena.
/// Throws aaf::Error on mismatched sizes or bad parameters.
void plan_samples(const SamplingPlanInputs &inputs, const LightPlane &light, const AafParams &aaf,
                  const SamplingPlanParams &params, PlaneView spp_out);

/// The plan for a first-pass AOV set that follows the contract (any
/// renderer's): returns a set holding the PlannedSpp channel and the input's
/// attributes. The light's sigma comes from the header. Throws aaf::Error
/// naming the first missing channel or attribute.
AovSet plan_samples_aovs(const AovSet &first_pass, const ChannelMap &channels, const AafParams &aaf,
                         const SamplingPlanParams &params);

}  // namespace aaf
