// Temporal integration of the ratio estimator's output by reverse
// reprojection (Heitz, Hill, McGuire 2018, Sec. 4.1 pass 5).
#include "aaf/core/methods/ratio/ratio_temporal.h"

#include <string>

#include "aaf/core/framework/temporal_window.h"
#include "aaf/core/util/error.h"

namespace aaf {

namespace {

void check_frame(const TemporalFrame &frame, int width, int height, const char *which) {
    auto check = [&](ConstPlaneView view) {
        if (!view.valid() || view.width != width || view.height != height)
            throw Error(std::string("temporal accumulation: the ") + which +
                        " frame's layers differ in size");
    };
    for (int c = 0; c < 3; ++c) {
        check(frame.colour[c]);
        check(frame.position[c]);
        check(frame.normal[c]);
    }
    check(frame.scale_m);
}

}  // namespace

void temporal_accumulate(const TemporalFrame &current, const std::array<ConstPlaneView, 2> &motion,
                         const TemporalFrame &previous, const TemporalSettings &settings,
                         const std::array<PlaneView, 3> &out) {
    const int width = current.colour[0].width, height = current.colour[0].height;
    check_frame(current, width, height, "current");
    check_frame(previous, width, height, "previous");
    for (int c = 0; c < 2; ++c)
        if (!motion[c].valid() || motion[c].width != width || motion[c].height != height)
            throw Error("temporal accumulation: the motion layer is missing or has another size");
    for (int c = 0; c < 3; ++c)
        if (!out[c].valid() || out[c].width != width || out[c].height != height)
            throw Error("temporal accumulation: an output is missing or has another size");
    if (!(settings.alpha > 0 && settings.alpha <= 1) || !(settings.plane_tolerance > 0))
        throw Error("temporal accumulation: alpha must be in (0, 1] and the plane tolerance > 0");
    // The temporal window's causal, recursive case: the same lookup of the
    // previous frame and the same tests of its surface.
    const auto view = [&motion](const TemporalFrame &frame, int offset) {
        TemporalFrameView v;
        v.offset = offset;
        v.values.assign(frame.colour.begin(), frame.colour.end());
        v.position = frame.position;
        v.normal = frame.normal;
        v.motion = motion;  // the current frame's: where each of its points was
        v.pixel_size_m = frame.scale_m;
        return v;
    };
    TemporalWindowSettings window;
    window.plane_tolerance = settings.plane_tolerance;
    window.normal_threshold_deg = settings.normal_threshold_deg;
    blend_temporal_history(view(current, 0), view(previous, -1), settings.alpha, window,
                           {out.begin(), out.end()});
}

}  // namespace aaf
