#pragma once

// isg-shadow's filter over whole planes (Robison and Shirley 2009, Sec. 3.1),
// apart from the method's parameters and the beauty's composition.
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/plane_view.h"
#include "isg_common.h"

namespace aaf::isg {

/// isg-shadow's settings, read from its parameters.
struct IsgShadowSettings : CommonSettings {
    TapShape light_shape = TapShape::Rectangle;  ///< the taps', the virtual light's (ISG Sec. 3.1)
    float light_scale = 1;                       ///< L of ISG Eq. 5 and 8 over the light's half-extent
    /// Not a parameter: false computes every pixel in full instead of
    /// passing over the blocks whose result is known (the same bits, slower).
    bool pass_over_uniform = true;
};

/// isg-shadow's settings from its `parameters` (Method::default_parameters() and the like).
IsgShadowSettings isg_shadow_settings(const ParameterSet &parameters);

/// The planes isg-shadow reads, of one size.
struct ShadowInputs {
    ConstPlaneView hard, occluder_m, depth_m;
    Vec3Planes position;
};

/// Per pixel: the parameter search (ISG Eq. 4-7), the mean occluder distance
/// of the in-shadow taps within the light's projected size (ISG Eq. 5);
/// then the gather (ISG Eq. 4) of the hard visibility within the penumbra's
/// projection (ISG Eq. 8-9), constant spatial weight, range of ISG Eq. 6-7.
/// A pixel with no occluder within reach keeps its hard value. Writes the
/// filtered visibility to `out` (the size of the inputs).
void isg_shadow_visibility(const ShadowInputs &in, const IsgShadowSettings &settings, const LightPlane &light,
                           float focal_px, PlaneView out);

}  // namespace aaf::isg
