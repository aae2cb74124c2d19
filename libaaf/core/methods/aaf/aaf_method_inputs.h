#pragma once

#include "aaf/core/framework/method.h"
#include "aaf/core/methods/aaf/aaf_filter.h"

namespace aaf {

/// AAF's per-pixel geometry from a method's images: d1, d2min, d2max,
/// position, normal, object id and pixel size (the caller sets the
/// visibility and the spp). Shared by `aaf filter aaf` and the ratio
/// estimator's `--denoiser aaf`, which read them under the same roles.
inline AafInputs aaf_geometry_inputs(const MethodImages &images) {
    AafInputs in;
    in.d1 = images.input(Role::D1);
    in.d2_min = images.input(Role::D2Min);
    in.d2_max = images.input(Role::D2Max);
    for (std::size_t c = 0; c < 3; ++c) {
        in.position[c] = images.input(Role::Position, c);
        in.normal[c] = images.input(Role::Normal, c);
    }
    in.object_id = images.input(Role::ObjectId);
    in.pixel_size = images.input(Role::PixelSize);
    return in;
}

}  // namespace aaf
