#pragma once

#include <cstddef>

#include "aaf/core/math/vec3.h"
#include "stratified_grid.h"

namespace aaf::trace {

/// One light sample of one pixel, as the renderer hands it to the AOV groups
/// (aov_group.h): the shadow ray from the pixel's primary hit towards a point
/// y of the light and, traced with it, the radiance that does not factor as
/// r(x) V(x).
struct LightSample {
    /// Index of the light in the scene's list; 0 is the key light, whose
    /// visibility the AAF AOVs describe. Renderer::trace_shadows emits the
    /// key light's samples only, with the other lights' shading in `radiance`.
    std::size_t light = 0;
    /// y in the light's stratified unit square [0, 1)^2, before the warp to
    /// its emission profile (s along the light's axis_u, t along axis_v).
    UnitPoint y_unit;
    /// y on the light's plane: metres from the light's centre along axis_u
    /// and axis_v (LightPlane::point_at(y_u_m, y_v_m) is the ray's target).
    float y_u_m = 0;
    float y_v_m = 0;
    /// u on the lens: metres from the lens centre along the camera's right
    /// and up axes; 0 for a pinhole camera.
    float lens_x_m = 0;
    float lens_y_m = 0;
    /// Light-function weight l(y) relative to the light's centre, unitless:
    /// 1, or with the cosine falloff inside l(y) (AAF Sec. 7)
    /// cos(receiver) cos(light) / r^2 relative to its value at the centre.
    double weight = 1.0;
    /// False for a pixel without a receiver (a thin lens's background pixel,
    /// which only gathers lens rays): then only `radiance` means anything.
    bool has_receiver = true;
    /// Whether the shadow ray reached the light.
    bool visible = true;
    /// When occluded: the occluder's distance from the light's plane along
    /// its normal, metres (d2 of AAF Fig. 2); for a light point behind the
    /// receiver's own tangent plane d1, or 0 (no occluder distance) with
    /// RenderSettings::skip_self_occluded; 0 when visible.
    float d2_m = 0;
    /// Radiance traced with this sample apart from r(x) V(x): the other
    /// lights' shadowed shading, or with a thin lens the whole radiance seen
    /// through the lens sample's ray; linear radiance, 0 when neither applies.
    Vec3 radiance;
};

}  // namespace aaf::trace
