#pragma once

#include <array>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/light_plane.h"
#include "aaf/core/contract/plane_view.h"
#include "aaf/core/framework/parameters.h"
#include "aaf/core/kernels/gather.h"
#include "aaf/core/methods/aaf/aaf_params.h"

namespace aaf {

/// Per-pixel inputs of the AAF filter, all of one size (see aov_contract.h for
/// meanings and units). d2_min/d2_max hold 0 where no occluder was hit.
struct AafInputs {
    ConstPlaneView visibility;
    ConstPlaneView d1;
    ConstPlaneView d2_min;
    ConstPlaneView d2_max;
    std::array<ConstPlaneView, 3> position;
    std::array<ConstPlaneView, 3> normal;
    ConstPlaneView object_id;
    ConstPlaneView pixel_size;
    ConstPlaneView spp;  ///< samples per pixel; read only with AafParams::mu_from_spp
};

/// Caller-owned outputs, same size as the inputs. `beta_m` may be left empty.
struct AafOutputs {
    PlaneView filtered_visibility;
    PlaneView beta_m;
};

/// Axis-Aligned Filtering of soft-shadow visibility (Mehta et al. 2012):
/// beta per pixel from AAF Eq. 13 (unoccluded pixels borrow occluder distances
/// from their neighbours, Sec. 6), then the world-space Gaussian of Eq. 10-12
/// as a vertical and a horizontal pass (Sec. 6), rejecting taps of another
/// object or with a normal beyond the threshold. Pixels with beta = 0 (no
/// occluder nearby, background) keep their input value. Runs on the current
/// oneTBB arena; the result does not depend on the thread count.
/// Throws aaf::Error on mismatched sizes or bad parameters.
void aaf_filter(const AafInputs &inputs, const LightPlane &light, const AafParams &params,
                const AafOutputs &outputs);

/// AAF as inputs to the shared gather (gather.h): positions in the light's
/// plane (AAF Eq. 12) and, per pixel, the Gaussian of AAF Eq. 11 with the
/// beta of AAF Eq. 13 and a reach of ceil(3 beta / pixel size) pixels;
/// `beta_m`, when valid, receives beta (world metres, 0 = not filtered).
/// aaf_filter() is this, then aaf_gather() of the visibility. Throws as aaf_filter.
GatherGuides aaf_gather_guides(const AafInputs &inputs, const LightPlane &light, const AafParams &params,
                               PlaneView beta_m = {});
/// The gather settings AafParams selects (normal threshold, separable or 2D).
GatherSettings aaf_gather_settings(const AafParams &params);
/// AAF's gather of `sources` into `outputs` (each may be its own source)
/// with the weights and tests of `guides` from aaf_gather_guides(): the
/// separable mode as AAF's own two passes (AAF Sec. 6, aaf_gather.cpp), the
/// same sums as gather() in that mode with each tap's exponential in base 2
/// and no fused multiply-add, so every instruction set gives the same bits;
/// the 2D mode is gather() itself. Throws aaf::Error on mismatched sizes.
void aaf_gather(const GatherGuides &guides, const AafParams &params,
                const std::vector<ConstPlaneView> &sources, const std::vector<PlaneView> &outputs);
/// aaf_filter()'s last step on guides aaf_gather_guides() made from the same
/// inputs and parameters: the gather of `visibility` (a non-finite value
/// read as 0) into `filtered_visibility`, which may be `visibility` itself.
/// Lets one set of guides serve further planes (a pass of the key light).
void aaf_filter_visibility(const GatherGuides &guides, const AafParams &params, ConstPlaneView visibility,
                           PlaneView filtered_visibility);

/// The "aaf" method's parameters, each declared once bound to its AafParams
/// member: the filter's options, `aaf info`, the Python module, and the
/// plan's options (aaf plan, render --adaptive) are generated from it.
const ParameterDeclarations<AafParams> &aaf_parameter_declarations();
/// The parameters a sampling plan (AAF Eq. 21: aaf plan, render --adaptive)
/// shares with the filter that follows it, which must be given the same:
/// mu, light_bandlimit, light_axes, pixel_footprint.
const std::vector<std::string> &aaf_plan_parameter_names();

/// The registered "aaf" method's parameters holding `params` (method_registry.h).
ParameterSet aaf_parameter_set(const AafParams &params);

/// Runs the registered "aaf" method (filter_aovs.h) on an AOV set that follows the contract: returns every
/// input channel, with the beauty replaced by r(x) times the filtered visibility (AAF Eq. 1), the input
/// beauty kept as the NoisyBeauty role, and the filtered visibility and beta added as their own layers. The
/// light comes from the header attributes. Throws aaf::Error naming the first missing channel.
AovSet aaf_filter_aovs(const AovSet &input, const ChannelMap &channels, const AafParams &params);

}  // namespace aaf
