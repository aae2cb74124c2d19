#include "renderer.h"

#include <algorithm>
#include <cmath>

#include "random.h"
#include "stratified_grid.h"

namespace aaf::trace {

namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr int kFalloffQuadrature = 16;  // per axis
/// Shadow rays end at this fraction of the way to the light point.
constexpr float kShadowRayReach = 1.0f - 1e-4f;

}  // namespace

Renderer::Renderer(const SceneDescription &scene, const RenderSettings &settings)
    : scene_(scene), settings_(settings), bvh_(scene), light_sampler_(scene.light) {}

float Renderer::falloff(Vec3 p, Vec3 n, Vec3 light_point) const {
    Vec3 to_light = light_point - p;
    const float distance_sq = dot(to_light, to_light);
    to_light = to_light / std::sqrt(distance_sq);
    const float cos_receiver = std::max(0.0f, dot(n, to_light));
    const float cos_light = std::max(0.0f, -dot(scene_.light.normal, to_light));
    return cos_receiver * cos_light / distance_sq;
}

float Renderer::mean_falloff(Vec3 p, Vec3 n) const {
    double sum = 0;
    for (int j = 0; j < kFalloffQuadrature; ++j)
        for (int i = 0; i < kFalloffQuadrature; ++i) {
            const UnitPoint cell{(i + 0.5f) / kFalloffQuadrature, (j + 0.5f) / kFalloffQuadrature};
            sum += falloff(p, n, light_sampler_.point(cell));
        }
    return float(sum / (kFalloffQuadrature * kFalloffQuadrature));
}

PrimaryHit Renderer::trace_primary(int x, int y) const {
    const PinholeCamera &camera = scene_.camera;
    const Vec3 direction = camera.ray_direction(x + 0.5f, y + 0.5f);
    const Hit hit = bvh_.intersect(camera.eye, direction, 0.0f, std::numeric_limits<float>::infinity());
    PrimaryHit primary;
    if (!hit.found) return primary;
    primary.found = true;
    primary.mesh = &scene_.meshes[hit.mesh_index];
    primary.position = camera.eye + direction * hit.distance;
    const Vec3 normal = normalize(hit.geometric_normal);
    primary.normal = dot(normal, direction) > 0 ? -normal : normal;
    primary.pixel_size_m = pixel_footprint(primary, x, y);

    // AAF Eq. 1: r(x) with the light's irradiance at its centre (or, with the
    // falloff inside l(y), the exact unshadowed irradiance), no visibility.
    const float geometry = settings_.cosine_falloff
                               ? mean_falloff(primary.position, primary.normal)
                               : falloff(primary.position, primary.normal, scene_.light.center);
    primary.unshadowed = primary.mesh->albedo * (scene_.light_intensity * geometry / kPi);
    return primary;
}

void Renderer::trace_shadows(const PrimaryHit &primary, std::uint64_t pixel_index, std::uint32_t pass,
                             std::uint32_t count, ShadowStats &stats) const {
    const LightPlane &light = scene_.light;
    PixelRng rng(settings_.seed, pixel_index, pass);
    const std::uint32_t stratum_key = rng.next_u32();
    const StratifiedGrid strata(count);
    // Offset along the camera-facing normal, scaled to the coordinates' magnitude.
    // Only light points in front of that normal are traced, so the origin
    // always lies on the side of the surface that faces the light point.
    const Vec3 p = primary.position;
    const float epsilon = 1e-4f * (1.0f + std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}));
    const Vec3 origin = p + primary.normal * epsilon;
    const float d1 = light.plane_distance_m(p);
    const float centre_falloff = settings_.cosine_falloff ? falloff(p, primary.normal, light.center) : 0.0f;
    for (std::uint32_t i = 0; i < count; ++i) {
        const float u1 = rng.next_float(), u2 = rng.next_float();
        const Vec3 target = light_sampler_.point(strata.point(i, stratum_key, u1, u2));
        // Samples follow the emission profile; the falloff, when included in l(y),
        // weights them relative to the centre (AAF Sec. 7).
        double weight = 1.0;
        if (settings_.cosine_falloff && centre_falloff > 0)
            weight = falloff(p, primary.normal, target) / centre_falloff;
        ++stats.taken;
        stats.weight_sum += weight;
        if (dot(primary.normal, target - p) <= 0) {
            // The light point lies behind the receiver's own tangent plane: the
            // (closed) surface occludes it at the receiver itself.
            stats.add_occluder(d1);
            continue;
        }
        // t = 1 reaches the light point; stop just short of it.
        const Vec3 direction = target - origin;
        const Hit hit = bvh_.intersect(origin, direction, 0.0f, kShadowRayReach);
        if (!hit.found) {
            stats.unoccluded_weight_sum += weight;
            continue;
        }
        stats.add_occluder(light.plane_distance_m(origin + direction * hit.distance));
    }
}

/// World size of the pixel at the hit: the rays through the neighbouring
/// pixel centres meet the hit's tangent plane; d = sqrt(|dP/dx x dP/dy|),
/// which includes foreshortening.
float Renderer::pixel_footprint(const PrimaryHit &primary, int x, int y) const {
    const PinholeCamera &camera = scene_.camera;
    const Vec3 n = primary.normal;
    const float plane_offset = dot(n, primary.position - camera.eye);
    auto on_plane = [&](Vec3 direction) {
        // Grazing rays are clamped to a 1e-3 cosine so the footprint stays finite.
        const float cosine = dot(n, direction);
        const float limit = 1e-3f * length(direction);
        const float denominator = std::fabs(cosine) < limit ? std::copysign(limit, cosine) : cosine;
        return camera.eye + direction * (plane_offset / denominator);
    };
    const Vec3 dx = on_plane(camera.ray_direction(x + 1.5f, y + 0.5f)) - primary.position;
    const Vec3 dy = on_plane(camera.ray_direction(x + 0.5f, y + 1.5f)) - primary.position;
    return std::sqrt(length(cross(dx, dy)));
}

}  // namespace aaf::trace
