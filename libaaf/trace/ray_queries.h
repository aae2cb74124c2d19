#pragma once

#include <algorithm>
#include <cmath>

#include "aaf/core/math/vec3.h"
#include "camera.h"

namespace aaf::trace {

/// The closest hit of a ray, or none.
struct Hit {
    bool found = false;
    float distance = 0;     ///< along the (unnormalised) ray direction, in units of its length
    Vec3 geometric_normal;  ///< unnormalised, the triangle's e1 x e2
    unsigned mesh_index = 0;
};

/// The ray queries the tracer and its AOV groups make of the scene's
/// geometry, and all they make: the seam between the shading code and the
/// acceleration structure (as pbrt-v4's WavefrontAggregate keeps its CPU and
/// OptiX aggregates apart). EmbreeScene implements it on the CPU; another
/// backend implements the three calls. Rays are origin + t direction for t
/// in [t_near, t_far]; every call is const and thread-safe, and a backend
/// answers a ray the same whatever else is in its batch, so results do not
/// depend on batching or threads.
class RayQueries {
  public:
    virtual ~RayQueries() = default;

    /// Closest hits of the camera's pinhole rays, eye + t
    /// camera.ray_direction(x + 0.5, y + 0.5) for t >= 0, through the pixel
    /// centres x in [x_begin, x_end) of row y: hits[x - x_begin].
    virtual void primary_hits(const Camera &camera, int y, int x_begin, int x_end, Hit *hits) const = 0;
    /// Whether anything lies on each of `count` rays from one origin,
    /// origin + t directions[k] (any hit answers it): blocked[k], k < count.
    virtual void occluded(Vec3 origin, const Vec3 *directions, int count, float t_near, float t_far,
                          bool *blocked) const = 0;
    /// The closest hit of one ray.
    virtual Hit closest_hit(Vec3 origin, Vec3 direction, float t_near, float t_far) const = 0;

    /// occluded() of a single ray.
    bool occluded(Vec3 origin, Vec3 direction, float t_near, float t_far) const {
        bool blocked = false;
        occluded(origin, &direction, 1, t_near, t_far, &blocked);
        return blocked;
    }
};

/// Shadow rays end at this fraction of the way to their light point (t = 1).
inline constexpr float kShadowRayReach = 1.0f - 1e-4f;

/// A ray origin at surface point `p`, offset along its (ray-facing) normal
/// `n`, scaled to the coordinates' magnitude so float rounding cannot put it
/// behind the surface.
inline Vec3 offset_ray_origin(Vec3 p, Vec3 n) {
    const float epsilon = 1e-4f * (1.0f + std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}));
    return p + n * epsilon;
}

/// Whether the shadow ray from surface point `p` (normal `n`, facing the
/// ray's side) to `target` is blocked: by the scene, or by the (closed)
/// surface itself when `target` lies behind p's tangent plane.
inline bool shadow_ray_blocked(const RayQueries &rays, Vec3 p, Vec3 n, Vec3 target) {
    if (dot(n, target - p) <= 0) return true;
    const Vec3 origin = offset_ray_origin(p, n);
    return rays.occluded(origin, target - origin, 0.0f, kShadowRayReach);
}

}  // namespace aaf::trace
