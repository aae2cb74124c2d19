#include "path_sample.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "aaf/core/math/concentric_disc.h"
#include "aaf/core/util/error.h"
#include "shading.h"

namespace aaf::trace {

namespace {

constexpr float kPi = 3.14159265358979323846f;

}  // namespace

unsigned parse_maaf6_effects(const std::string &list) {
    unsigned effects = 0;
    std::stringstream items(list);
    for (std::string item; std::getline(items, item, ',');) {
        if (item == "defocus")
            effects |= kMaaf6Defocus;
        else if (item == "shadows")
            effects |= kMaaf6Shadows;
        else if (item == "indirect")
            effects |= kMaaf6Indirect;
        else if (item == "all")
            effects |= kMaaf6Defocus | kMaaf6Shadows | kMaaf6Indirect;
        else
            throw Error("unknown maaf6 effect '" + item + "' (known: defocus, shadows, indirect, all)");
    }
    if (effects == 0) throw Error("maaf6 effects: name at least one of defocus, shadows, indirect");
    return effects;
}

std::string maaf6_effects_name(unsigned effects) {
    std::string name;
    for (const auto &[flag, word] : {std::pair<unsigned, const char *>{kMaaf6Defocus, "defocus"},
                                     {kMaaf6Shadows, "shadows"},
                                     {kMaaf6Indirect, "indirect"}})
        if (effects & flag) name += (name.empty() ? "" : ",") + std::string(word);
    return name;
}

PathSampler::PathSampler(const SceneDescription &scene, const RayQueries &rays, unsigned effects)
    : scene_(scene), rays_(rays), light_(scene.key_light()), effects_(effects) {}

Vec3 PathSampler::direct_light(const Mesh &mesh, Vec3 p, Vec3 n, Vec3 eye, Vec3 light_point, bool &visible,
                               float &occluder_plane_distance_m) const {
    const SceneLight &light = scene_.lights.front();
    visible = false;
    occluder_plane_distance_m = 0;
    Vec3 to_light = light_point - p;
    const float distance_sq = dot(to_light, to_light);
    if (!(distance_sq > 0) || dot(n, to_light) <= 0) return {};  // behind the receiver's tangent plane
    const Vec3 origin = offset_ray_origin(p, n);
    const Vec3 direction = light_point - origin;
    const Hit blocker = rays_.closest_hit(origin, direction, 0.0f, kShadowRayReach);
    if (blocker.found)
        occluder_plane_distance_m = light.plane.plane_distance_m(origin + direction * blocker.distance);
    visible = !blocker.found;
    to_light = to_light / std::sqrt(distance_sq);
    const float cos_receiver = std::max(0.0f, dot(n, to_light));
    const float cos_light = std::max(0.0f, -dot(light.plane.normal, to_light));
    const float geometry = cos_receiver * cos_light / std::max(distance_sq, 1e-12f);
    const Vec3 brdf = evaluate_brdf(mesh.material, n, normalize(eye - p), to_light);
    return times(brdf, light.color) * (light.intensity * geometry);
}

PathSample PathSampler::trace(int x, int y, const PathSampleNumbers &numbers) const {
    const Camera &camera = scene_.camera;
    PathSample sample;
    // The primary lens ray (MAAF Sec. 6.2): from a point of the aperture to the pixel centre's focus point.
    Vec3 lens = camera.eye;
    if ((effects_ & kMaaf6Defocus) && camera.is_thin_lens()) {
        const DiscPoint d = concentric_disc_unit(numbers.lens.s, numbers.lens.t);
        sample.lens_offset_m = (camera.right * d.x + camera.up * d.y) * camera.aperture_radius_m;
        lens = camera.eye + sample.lens_offset_m;
    }
    const Vec3 focus_or_direction = camera.ray_direction(x + 0.5f, y + 0.5f);
    const Vec3 direction = camera.is_thin_lens()
                               ? camera.eye + focus_or_direction * camera.focus_distance_m - lens
                               : focus_or_direction;
    const Hit hit = rays_.closest_hit(lens, direction, 0.0f, std::numeric_limits<float>::infinity());
    if (!hit.found) return sample;
    sample.hit = true;
    const Mesh &mesh = scene_.meshes[hit.mesh_index];
    const Vec3 p = lens + direction * hit.distance;
    Vec3 n = normalize(hit.geometric_normal);
    n = dot(n, direction) > 0 ? -n : n;
    sample.depth_m = dot(p - camera.eye, camera.forward);

    // Direct: one shadow ray to the area light (its centre with the shadows effect off).
    const LightPlane &plane = scene_.key_light();
    const Vec3 light_point = (effects_ & kMaaf6Shadows) ? light_.point(numbers.light) : plane.center;
    sample.light_offset_m = light_point - plane.center;
    bool visible;
    float d2_m;
    sample.direct_unoccluded = direct_light(mesh, p, n, lens, light_point, visible, d2_m);
    if (visible) sample.direct = sample.direct_unoccluded;
    // A point light (the shadows effect off) has no y extent, hence no y-wedge.
    if (d2_m > 0 && (effects_ & kMaaf6Shadows))
        sample.direct_slope = std::max(0.0f, plane.plane_distance_m(p) / d2_m - 1.0f);  // MAAF Sec. 3

    // Indirect: a cosine-distributed bounce with its own shadow ray.
    if (!(effects_ & kMaaf6Indirect)) return sample;
    const float radius = std::sqrt(numbers.bounce.s), phi = 2 * kPi * numbers.bounce.t;
    const Vec3 helper = std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 b1 = normalize(cross(n, helper)), b2 = cross(n, b1);
    const Vec3 omega = normalize(b1 * (radius * std::cos(phi)) + b2 * (radius * std::sin(phi)) +
                                 n * std::sqrt(std::max(0.0f, 1 - numbers.bounce.s)));
    sample.bounce_direction = omega;
    const Vec3 origin = offset_ray_origin(p, n);
    const Hit bounce = rays_.closest_hit(origin, omega, 0.0f, std::numeric_limits<float>::infinity());
    if (!bounce.found) return sample;
    const Vec3 q = origin + omega * bounce.distance;
    Vec3 nq = normalize(bounce.geometric_normal);
    nq = dot(nq, omega) > 0 ? -nq : nq;
    sample.bounce_height_m = std::max(1e-4f, dot(q - p, n));  // s = z of MAAF Sec. 3 (AAF-GI)
    const Vec3 bounce_light = (effects_ & kMaaf6Shadows) ? light_.point(numbers.bounce_light) : plane.center;
    bool bounce_visible;
    float bounce_d2_m;
    const Vec3 reflected =
        direct_light(scene_.meshes[bounce.mesh_index], q, nq, p, bounce_light, bounce_visible, bounce_d2_m);
    if (bounce_visible)
        sample.indirect = times(mesh.material.albedo, reflected);  // (albedo / pi) cos / (cos / pi)
    return sample;
}

}  // namespace aaf::trace
