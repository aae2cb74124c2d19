#pragma once

#include <array>

#include "aaf/core/contract/plane_view.h"

namespace aaf {

/// One frame as temporal accumulation sees it; views of one size.
struct TemporalFrame {
    std::array<ConstPlaneView, 3> colour;    ///< this frame's image (previous: the accumulated one)
    std::array<ConstPlaneView, 3> position;  ///< world metres
    std::array<ConstPlaneView, 3> normal;    ///< unit
    /// World length one pixel covers (the PixelSize role or a scene-bounds
    /// scale); a non-positive or non-finite value marks no surface.
    ConstPlaneView scale_m;
};

struct TemporalSettings {
    /// Weight of the current frame in the exponential history (1 = no history).
    float alpha = 0.2f;
    /// A history tap is rejected (disocclusion) when its position lies farther
    /// than this many of the current pixel's footprints from the current
    /// pixel's tangent plane, or ...
    float plane_tolerance = 2.0f;
    /// ... when its normal turns by more than this from the current one; degrees.
    float normal_threshold_deg = 25.0f;
};

/// Reverse reprojection with exponential history (ratio estimator Sec. 4.1,
/// pass 5): each pixel looks up where its surface was in the previous frame
/// (raster position minus `motion`, pixels, y down: the Motion role),
/// bilinearly over the 4 nearest previous pixels, keeping only taps on the
/// same surface (tangent-plane distance and normal, as above; their bilinear
/// weights renormalised), and writes alpha x current + (1 - alpha) x history;
/// where no tap survives (disocclusion, off screen) the current colour.
/// Non-finite history taps are rejected. `out` may alias current.colour.
/// The temporal window's causal, recursive case (blend_temporal_history()).
/// Deterministic, any thread count; throws aaf::Error on mismatched sizes.
void temporal_accumulate(const TemporalFrame &current, const std::array<ConstPlaneView, 2> &motion,
                         const TemporalFrame &previous, const TemporalSettings &settings,
                         const std::array<PlaneView, 3> &out);

}  // namespace aaf
