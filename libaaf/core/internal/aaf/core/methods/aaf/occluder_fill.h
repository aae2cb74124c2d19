#pragma once

#include <vector>

#include "aaf/core/contract/plane_view.h"
#include "aaf/core/util/frame_allocator.h"

namespace aaf {

/// Occluder distances per pixel after AAF Sec. 6's fill: where a pixel's own
/// shadow rays hit no occluder (d2max = 0), the mean d2min/d2max of occluded
/// pixels of the same object within `radius_px` (a disc); 0 where there is none.
/// d1 is known at every pixel and is not borrowed. Row-major, width x height.
struct FilledOccluders {
    FramePlane<float> d2_min_m;
    FramePlane<float> d2_max_m;
};

/// Computes the fill on the current oneTBB arena (thread-count independent).
FilledOccluders fill_occluder_distances(ConstPlaneView d2_min, ConstPlaneView d2_max,
                                        ConstPlaneView object_id, int radius_px);

/// True where a shadow ray hit an occluder: a positive, finite d2max.
inline bool has_occluder(float d2_max_m) {
    return d2_max_m > 0 && d2_max_m < 3.0e38f;
}

}  // namespace aaf
