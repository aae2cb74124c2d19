#pragma once

#include <cstdint>
#include <string>

#include "aaf/core/math/vec3.h"
#include "light_sampler.h"
#include "ray_queries.h"
#include "scene_description.h"

namespace aaf::trace {

/// Which effects a maaf6 path sample traces (RenderSettings::maaf6_effects).
enum Maaf6Effect : unsigned {
    kMaaf6Defocus = 1u << 0,   ///< lens points over the aperture; off: the lens centre (pinhole)
    kMaaf6Shadows = 1u << 1,   ///< light points over the area light; off: its centre (hard shadows)
    kMaaf6Indirect = 1u << 2,  ///< the one-bounce indirect layer; off: 0
};
/// Parses "defocus,shadows,indirect" (any subset, at least one; "all" = the
/// three); throws aaf::Error naming an unknown item.
unsigned parse_maaf6_effects(const std::string &list);
/// The canonical spelling of `effects`, as parse_maaf6_effects() reads it.
std::string maaf6_effects_name(unsigned effects);

/// The random numbers of one path sample, each pair in [0, 1)^2.
struct PathSampleNumbers {
    UnitPoint lens, light, bounce, bounce_light;
};

/// One path sample of MAAF Sec. 6.2 ("Sampling"): a primary lens ray, a shadow
/// ray to the key light, and a one-bounce diffuse indirect sample with its
/// own shadow ray at the bounce point. Radiances are linear, per channel.
struct PathSample {
    bool hit = false;            ///< whether the lens ray hit anything
    Vec3 direct, indirect;       ///< radiance towards the lens point
    Vec3 direct_unoccluded;      ///< `direct` with the shadow ray's visibility taken as 1
    Vec3 lens_offset_m;          ///< lens point minus lens centre, world metres
    Vec3 light_offset_m;         ///< light point minus light centre, world metres
    Vec3 bounce_direction;       ///< unit, from the hit (0 when the indirect layer is off)
    float depth_m = 0;           ///< hit depth along the camera's forward axis
    float direct_slope = -1;     ///< d1/d2 - 1 when the shadow ray is blocked (area light), else -1
    float bounce_height_m = -1;  ///< reflector distance along the hit's normal, -1 without a reflector
};

/// Traces MAAF path samples through a scene's RayQueries (thread-safe, const).
///
/// Direct: the key light's BRDF times its colour, intensity and
/// cos(receiver) cos(light) / r^2 towards the sampled light point, times
/// that shadow ray's visibility (the other lights are not traced).
/// Indirect: a cosine-distributed direction about the hit's normal; the
/// surface it reaches, lit the same way with a shadow ray of its own, times
/// the hit's diffuse albedo (cosine sampling cancels cos / pi); specular
/// lobes do not scatter the bounce. Lens rays start on the aperture
/// (concentric map) and aim at the pixel centre's point on the plane in
/// focus, as the tracer's thin lens does.
class PathSampler {
  public:
    PathSampler(const SceneDescription &scene, const RayQueries &rays, unsigned effects);

    PathSample trace(int x, int y, const PathSampleNumbers &numbers) const;

  private:
    /// Radiance of the key light's point `light_point` reflected at p towards
    /// `eye` with visibility 1 (0 behind p's tangent plane); `visible` and
    /// the occluder's light-plane distance (0 when none) from its shadow ray.
    Vec3 direct_light(const Mesh &mesh, Vec3 p, Vec3 n, Vec3 eye, Vec3 light_point, bool &visible,
                      float &occluder_plane_distance_m) const;

    const SceneDescription &scene_;
    const RayQueries &rays_;
    LightSampler light_;
    unsigned effects_;
};

}  // namespace aaf::trace
