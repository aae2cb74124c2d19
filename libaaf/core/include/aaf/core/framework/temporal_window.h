#pragma once

#include <array>
#include <vector>

#include "aaf/core/contract/plane_view.h"

namespace aaf {

/// How a filtered frame is blended with its filtered neighbours
/// (`aaf filter METHOD --temporal-window K`).
struct TemporalWindowSettings {
    /// K: the frames t-K..t+K around frame t are read (t-K..t when causal); 0 = none.
    int radius_frames = 0;
    /// Only earlier frames: what a frame's output depends on is known when it is made.
    bool causal = false;
    /// A neighbour's tap is rejected (disocclusion) when its position lies farther
    /// than this many of the pixel's footprints from the pixel's tangent plane, ...
    float plane_tolerance = 2.0f;
    /// ... when its normal turns by more than this, degrees, or when its object id differs.
    float normal_threshold_deg = 25.0f;
    /// A neighbour's value is down-weighted when it differs from the frame's
    /// own by more than the residual noise: its weight is exp(-e^2 / (2 (tau
    /// sigma)^2)), e the largest absolute difference over the blended
    /// channels, sigma the noise around the pixel: the robust scale of the
    /// differences over the pixel's region (1.4826 x the median of its non-zero
    /// values; with fewer than kTemporalRobustValues values, 0, no change
    /// allowed, when most of the region's are 0), bounded by the median over
    /// the region of its pixels' own spreads across the window (their values'
    /// median absolute deviation), 0 where the pixel's own values are mostly
    /// the same or where it repeats the value of two of its four neighbours in
    /// the frame (noise-free), and raised (kTemporalOwnScaleLimit) where the
    /// pixel spreads more than its region and as many of its frames follow as
    /// precede. A shadow or a light that moves over still geometry changes the
    /// value far beyond the noise and does not ghost. tau is this.
    float shading_tolerance = 3.0f;
};

/// The shading test measures the noise once per square block of this side,
/// over the region of kTemporalScaleRegionBlocks x kTemporalScaleRegionBlocks
/// blocks centred on it (20 x 20 pixels): wide enough that an edge moving a
/// few pixels a frame stays a minority of it, centred so that it follows
/// the noise where it changes within a frame.
inline constexpr int kTemporalBlockPx = 4;
inline constexpr int kTemporalScaleRegionBlocks = 5;
/// A pixel noisier than its region (where the filter's width changes) is
/// measured by its own values across a centred window (their median
/// absolute deviation): up to this many times its region's noise where a
/// neighbour's value is resampled (a moving camera or object) or fewer than
/// kTemporalRobustValues values measure it; else without a limit, a
/// neighbour farther than the tolerance times that spread being a change.
inline constexpr float kTemporalOwnScaleLimit = 3.0f;
/// From this many values at a pixel (its centre's and its neighbours'
/// surviving the surface tests), the median absolute deviation of its own
/// values ignores a change in up to two of them, so a moving edge shows as
/// a pixel whose own values agree; its region's noise is then measured over
/// the pixels that change at all, however few (a penumbra in a noise-free
/// region). With fewer, a region where most pixels do not change has no
/// noise: its changing pixels are an edge that moved.
inline constexpr int kTemporalRobustValues = 5;

/// Which extreme over the window temporal_window_extrema() takes.
enum class WindowExtreme {
    Min,
    Max,
    /// The smallest value not below 0: negative values mark "none" (MAAF 6D's
    /// -1 for a pixel without a y-wedge) and stay only where no frame has another.
    MinNonNegative,
};

/// One frame of the window as the blend reads it; views of one size.
struct TemporalFrameView {
    /// The frame's number minus the centre frame's.
    int offset = 0;
    /// The per-frame filtered planes to blend, in the same order in every frame.
    std::vector<ConstPlaneView> values;
    std::array<ConstPlaneView, 3> position;  ///< world metres
    std::array<ConstPlaneView, 3> normal;    ///< unit
    /// Raster position of the pixel's surface point in this frame minus in
    /// the previous one, pixels, y down (Role::Motion).
    std::array<ConstPlaneView, 2> motion;
    /// Optional (an invalid view: not tested): taps on another object are rejected.
    ConstPlaneView object_id;
    /// World length one pixel covers; optional (an invalid view: estimated
    /// from the positions of the pixel's neighbours). Non-positive or
    /// non-finite: no surface, the pixel keeps its own value.
    ConstPlaneView pixel_size_m;
};

/// Blends the centre frame's `values` with its neighbours' into `out` (same
/// count and size; `out` may alias nothing of the inputs): each neighbour is
/// looked up where the pixel's surface point was or will be, by following the
/// motion layers frame to frame (a neighbour past a missing frame is not
/// used), bilinearly over its 4 nearest pixels, keeping only taps on the same
/// surface (tangent-plane distance, normal, object id; their bilinear weights
/// renormalised), weighted by the shading test above; every frame in the
/// window weighs alike otherwise (a box in time), the centre frame 1. A
/// static frame whose neighbours hold the same values is unchanged, bit for
/// bit. Deterministic for any thread count. `neighbours` are sorted by
/// offset or not, any subset of the window; throws aaf::Error on mismatched
/// sizes or a missing layer.
void blend_temporal_window(const TemporalFrameView &centre, const std::vector<TemporalFrameView> &neighbours,
                           const TemporalWindowSettings &settings, const std::vector<PlaneView> &out);

/// The smallest (largest, `extreme`) of each of the centre's `values` over
/// the window: its own and every neighbour's at the pixel's surface point
/// (each of the taps blend_temporal_window() would keep, taken alone), into
/// `out` (same count and size; may alias nothing of the inputs). A filter's
/// width inputs so combined hold still from frame to frame (AAF's occluder
/// distances: their extremes over more samples). Pixels without a surface
/// keep their own values. Deterministic for any thread count; throws
/// aaf::Error on mismatched sizes.
void temporal_window_extrema(const TemporalFrameView &centre,
                             const std::vector<TemporalFrameView> &neighbours,
                             const TemporalWindowSettings &settings, WindowExtreme extreme,
                             const std::vector<PlaneView> &out);

/// The causal, recursive case (the ratio estimator's `--temporal`, its Sec.
/// 4.1 pass 5): `history` (offset -1; its `values` the previous frame's
/// output, its geometry the previous frame's) is looked up where the
/// centre's surface points were, as blend_temporal_window() looks up a
/// neighbour (the centre's motion, bilinear over the taps on the same
/// surface), and `out` = alpha x centre + (1 - alpha) x history where a tap
/// survives, the centre's value elsewhere: an exponential history, with no
/// shading test. `out` may alias the centre's values. Deterministic for any
/// thread count; throws aaf::Error on mismatched sizes or alpha outside (0, 1].
void blend_temporal_history(const TemporalFrameView &centre, const TemporalFrameView &history, float alpha,
                            const TemporalWindowSettings &settings, const std::vector<PlaneView> &out);

}  // namespace aaf
