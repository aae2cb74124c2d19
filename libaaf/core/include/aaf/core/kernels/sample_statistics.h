#pragma once

#include "aaf/core/contract/plane_view.h"

namespace aaf {

/// Mean of `samples_per_pixel` over shaded pixels (object id != 0): background
/// pixels take no light samples, so this is the "avg spp" of AAF Table 1.
/// Returns 0 when no pixel is shaded. Planes must have the same size.
double mean_spp_over_shaded(ConstPlaneView samples_per_pixel, ConstPlaneView object_id);

}  // namespace aaf
