#include "renderer.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "aaf/core/math/concentric_disc.h"
#include "aov_group.h"
#include "embree_scene.h"
#include "random.h"
#include "shading.h"
#include "stratified_grid.h"
#include "surface_texture.h"

namespace aaf::trace {

namespace {

constexpr int kFalloffQuadrature = 16;  // per axis
/// Floor of a squared receiver-light distance, (1e-6 m)^2.
constexpr float kMinDistanceSq_m2 = 1e-12f;
/// Samples whose light points are generated together (trace_shadows).
constexpr std::uint32_t kSampleBatch = 64;
/// Distinguishes the lens and other-light random numbers from the key light's.
constexpr std::uint64_t kSecondaryStream = 0x5bd1e9955bd1e995ull;

/// The EmbreeScene of a render with `settings`.
std::unique_ptr<EmbreeScene> embree_scene_for(const SceneDescription &scene, const RenderSettings &settings,
                                              ShadowRayGrouping grouping) {
    const bool reference = settings.spp >= kSamplesPerRound;
    // Packets where they measured faster: with a reference's high-quality
    // BVH, every shipped scene (1.02-1.43x end to end at 2048 spp) and the
    // 129k-triangle mesh (even); with the medium BVH of shorter renders they
    // lost on the mesh (0.83x, bench_trace). The answers are the same.
    // Closest hits (occluder distances) stay one ray at a time:
    // rtcIntersect16 changed d2min/d2max of 3 of 1200 grids pixels against
    // rtcIntersect1 (tried and measured, not adopted).
    const bool packets =
        grouping == ShadowRayGrouping::Packets || (grouping == ShadowRayGrouping::Automatic && reference);
    return std::make_unique<EmbreeScene>(scene, reference, true, packets);
}

}  // namespace

Renderer::Renderer(const SceneDescription &scene, const RenderSettings &settings, ShadowRayGrouping grouping)
    : Renderer(scene, settings, embree_scene_for(scene, settings, grouping)) {}

Renderer::Renderer(const SceneDescription &scene, const RenderSettings &settings, const RayQueries &rays)
    : scene_(scene), settings_(settings), rays_(rays) {
    for (const SceneLight &light : scene.lights) light_samplers_.emplace_back(light.plane);
}

Renderer::Renderer(const SceneDescription &scene, const RenderSettings &settings,
                   std::unique_ptr<EmbreeScene> owned)
    : scene_(scene), settings_(settings), owned_rays_(std::move(owned)), rays_(*owned_rays_) {
    for (const SceneLight &light : scene.lights) light_samplers_.emplace_back(light.plane);
}

Renderer::~Renderer() = default;

float Renderer::falloff(const LightPlane &light, Vec3 p, Vec3 n, Vec3 light_point) const {
    Vec3 to_light = light_point - p;
    const float distance_sq = dot(to_light, to_light);
    if (!(distance_sq > 0)) return 0;  // a receiver on the light point: no direction
    to_light = to_light / std::sqrt(distance_sq);
    const float cos_receiver = std::max(0.0f, dot(n, to_light));
    const float cos_light = std::max(0.0f, -dot(light.normal, to_light));
    // The scene's shortest length (1e-6 m, SCENE_FORMAT.md "Limits") bounds
    // 1 / r^2 at 1e12, so the radiance stays finite (its intensity bound's reason).
    return cos_receiver * cos_light / std::max(distance_sq, kMinDistanceSq_m2);
}

float Renderer::mean_falloff(Vec3 p, Vec3 n) const {
    double sum = 0;
    for (int j = 0; j < kFalloffQuadrature; ++j)
        for (int i = 0; i < kFalloffQuadrature; ++i) {
            const UnitPoint cell{(i + 0.5f) / kFalloffQuadrature, (j + 0.5f) / kFalloffQuadrature};
            sum += falloff(scene_.key_light(), p, n, light_samplers_[0].point(cell));
        }
    return float(sum / (kFalloffQuadrature * kFalloffQuadrature));
}

Vec3 Renderer::unshadowed(std::size_t light_index, const Mesh &mesh, Vec3 p, Vec3 n, Vec3 eye) const {
    const SceneLight &light = scene_.lights[light_index];
    // Shaded with the texture's albedo and the normal map's normal (the
    // geometric normal still decides occlusion).
    const TexturedSurface surface = texture_surface(mesh.material, p, n);
    // With the falloff inside l(y) (AAF Sec. 7), the key light's r(x) is the
    // exact unshadowed irradiance; otherwise the irradiance at the light's centre.
    const float geometry = light_index == 0 && settings_.cosine_falloff
                               ? mean_falloff(p, surface.normal)
                               : falloff(light.plane, p, surface.normal, light.plane.center);
    const Vec3 brdf = evaluate_brdf(surface.material, surface.normal, normalize(eye - p),
                                    normalize(light.plane.center - p));
    return times(brdf, light.color) * (light.intensity * geometry);
}

PrimaryHit Renderer::trace_primary(int x, int y) const {
    PrimaryHit primary;
    trace_primaries(y, x, x + 1, &primary);
    return primary;
}

void Renderer::trace_primaries(int y, int x_begin, int x_end, PrimaryHit *primaries) const {
    constexpr int kRowBatch = 64;
    std::array<Hit, kRowBatch> hits;
    for (int first = x_begin; first < x_end; first += kRowBatch) {
        const int last = std::min(first + kRowBatch, x_end);
        rays_.primary_hits(scene_.camera, y, first, last, hits.data());
        for (int x = first; x < last; ++x)
            primaries[x - x_begin] = primary_from(hits[std::size_t(x - first)], x, y);
    }
}

PrimaryHit Renderer::primary_from(const Hit &hit, int x, int y) const {
    const Camera &camera = scene_.camera;
    const Vec3 direction = camera.ray_direction(x + 0.5f, y + 0.5f);  // as RayQueries::primary_hits
    PrimaryHit primary;
    if (!hit.found) return primary;
    primary.found = true;
    primary.mesh = &scene_.meshes[hit.mesh_index];
    primary.position = camera.eye + direction * hit.distance;
    primary.depth_m = hit.distance;  // the direction's forward component is 1
    const Vec3 normal = normalize(hit.geometric_normal);
    primary.normal = dot(normal, direction) > 0 ? -normal : normal;
    primary.pixel_size_m = pixel_footprint(primary, x, y);
    primary.unshadowed = unshadowed(0, *primary.mesh, primary.position, primary.normal, camera.eye);
    return primary;
}

bool Renderer::light_point_blocked(const PrimaryHit &primary, Vec3 light_point) const {
    return occluded(primary.position, primary.normal, light_point);
}

bool Renderer::occluded(Vec3 p, Vec3 n, Vec3 target) const {
    return shadow_ray_blocked(rays_, p, n, target);
}

Vec3 Renderer::shade(const Mesh &mesh, Vec3 p, Vec3 n, Vec3 eye, UnitPoint u, std::size_t first_light) const {
    Vec3 radiance;
    for (std::size_t l = first_light; l < scene_.lights.size(); ++l)
        if (!occluded(p, n, light_samplers_[l].point(u)))
            radiance = radiance + unshadowed(l, mesh, p, n, eye);
    return radiance;
}

void Renderer::trace_key_light(const PrimaryHit &primary, Vec3 origin, float d1, float centre_falloff,
                               bool occluder_distances, const bool *traced_visibility,
                               LightSample &sample) const {
    const LightPlane &light = scene_.key_light();
    const Vec3 target = light.point_at(sample.y_u_m, sample.y_v_m);  // LightSampler::point
    const Vec3 p = primary.position;
    // Samples follow the emission profile; the falloff, when included in
    // l(y), weights them relative to the centre (AAF Sec. 7).
    if (settings_.cosine_falloff && centre_falloff > 0)
        sample.weight = falloff(light, p, primary.normal, target) / centre_falloff;
    if (dot(primary.normal, target - p) <= 0) {
        sample.visible = false;  // behind the receiver's own tangent plane
        sample.d2_m = settings_.skip_self_occluded || !occluder_distances ? 0.0f : d1;
        return;
    }
    // t = 1 reaches the light point; stop just short of it.
    const Vec3 direction = target - origin;
    if (!occluder_distances) {
        // Visibility alone: any hit answers it (rtcOccluded1), d2_m stays 0.
        sample.visible = traced_visibility ? *traced_visibility
                                           : !rays_.occluded(origin, direction, 0.0f, kShadowRayReach);
        return;
    }
    const Hit hit = rays_.closest_hit(origin, direction, 0.0f, kShadowRayReach);
    if (hit.found) {
        sample.visible = false;
        sample.d2_m = light.plane_distance_m(origin + direction * hit.distance);
    }
}

void Renderer::trace_visibility_batch(const PrimaryHit &primary, Vec3 origin, std::uint32_t count,
                                      const float *y_u_m, const float *y_v_m, bool *visible) const {
    const LightPlane &light = scene_.key_light();
    // The rays trace_key_light would trace (light points in front of the
    // tangent plane), a batch of kSampleBatch at a time.
    std::array<Vec3, kSampleBatch> directions;
    std::array<std::uint32_t, kSampleBatch> sample_of;
    std::array<bool, kSampleBatch> blocked;
    int filled = 0;
    auto flush = [&] {
        rays_.occluded(origin, directions.data(), filled, 0.0f, kShadowRayReach, blocked.data());
        for (int r = 0; r < filled; ++r) visible[sample_of[std::size_t(r)]] = !blocked[std::size_t(r)];
        filled = 0;
    };
    for (std::uint32_t k = 0; k < count; ++k) {
        const Vec3 target = light.point_at(y_u_m[k], y_v_m[k]);  // as trace_key_light
        visible[k] = false;  // behind the tangent plane, unless traced below
        if (dot(primary.normal, target - primary.position) <= 0) continue;
        directions[std::size_t(filled)] = target - origin;
        sample_of[std::size_t(filled)] = k;
        if (++filled == int(kSampleBatch)) flush();
    }
    if (filled > 0) flush();
}

void Renderer::trace_distance_batch(const PrimaryHit &primary, Vec3 origin, float d1, std::uint32_t count,
                                    const float *y_u_m, const float *y_v_m, bool *visible,
                                    ShadowStats &stats) const {
    const LightPlane &light = scene_.key_light();
    // A light point behind the tangent plane is occluded by the receiver
    // itself, d2 = d1, unless such samples are skipped (as trace_key_light).
    const float self_occluder_m = settings_.skip_self_occluded ? 0.0f : d1;
    for (std::uint32_t k = 0; k < count; ++k) {
        const Vec3 target = light.point_at(y_u_m[k], y_v_m[k]);
        float d2_m = self_occluder_m;
        visible[k] = false;
        if (dot(primary.normal, target - primary.position) > 0) {
            const Vec3 direction = target - origin;
            const Hit hit = rays_.closest_hit(origin, direction, 0.0f, kShadowRayReach);
            visible[k] = !hit.found;
            d2_m = hit.found ? light.plane_distance_m(origin + direction * hit.distance) : 0.0f;
        }
        if (d2_m > 0) stats.add_occluder(d2_m);  // as ShadowStats::add
    }
}

Vec3 Renderer::separate_radiance(const PrimaryHit &primary, Vec3 focus, PixelRng &lens_rng,
                                 LightSample &sample) const {
    const Camera &camera = scene_.camera;
    if (!camera.is_thin_lens())
        return shade(*primary.mesh, primary.position, primary.normal, camera.eye, sample.y_unit, 1);
    // A ray from a point of the aperture through the pixel centre's point on
    // the plane in focus; its hit is shaded by every light.
    // The second coordinate is drawn first: the order GCC gave the two draws
    // when they were arguments of one call, which the shipped renders keep.
    const float u2 = lens_rng.next_float();
    const float u1 = lens_rng.next_float();
    const DiscPoint disc = concentric_disc_unit(u1, u2);
    const float dx = disc.x, dy = disc.y;
    sample.lens_x_m = dx * camera.aperture_radius_m;
    sample.lens_y_m = dy * camera.aperture_radius_m;
    const Vec3 lens = camera.eye + (camera.right * dx + camera.up * dy) * camera.aperture_radius_m;
    const Vec3 direction = focus - lens;
    const Hit hit = rays_.closest_hit(lens, direction, 0.0f, std::numeric_limits<float>::infinity());
    if (!hit.found) return {};
    const Vec3 hit_point = lens + direction * hit.distance;
    Vec3 n = normalize(hit.geometric_normal);
    n = dot(n, direction) > 0 ? -n : n;
    return shade(scene_.meshes[hit.mesh_index], hit_point, n, lens, sample.y_unit, 0);
}

void Renderer::trace_shadows(const PrimaryHit &primary, int x, int y, std::uint64_t pixel_index,
                             std::uint32_t pass, std::uint32_t count, bool occluder_distances,
                             ShadowStats &stats, const std::vector<AovAccumulator *> &listeners) const {
    const LightPlane &light = scene_.key_light();
    const Camera &camera = scene_.camera;
    PixelRng rng(settings_.seed, pixel_index, pass);
    PixelRng secondary_rng(settings_.seed ^ kSecondaryStream, pixel_index, pass);
    const std::uint32_t stratum_key = rng.next_u32();
    const StratifiedGrid strata(count);
    // Only light points in front of the camera-facing normal are traced, so
    // the offset origin always lies on the side that faces the light point.
    const Vec3 p = primary.position;
    const Vec3 origin = offset_ray_origin(p, primary.normal);
    const float d1 = primary.found ? light.plane_distance_m(p) : 0.0f;
    const float centre_falloff =
        settings_.cosine_falloff && primary.found ? falloff(light, p, primary.normal, light.center) : 0.0f;
    const bool separate = has_separate_radiance();
    // Thin lens: the pixel centre's point on the plane in focus, where every lens ray aims.
    const Vec3 focus = camera.is_thin_lens()
                           ? camera.eye + camera.ray_direction(x + 0.5f, y + 0.5f) * camera.focus_distance_m
                           : Vec3{};
    // Visibility only, every weight 1 and nothing else traced or listened
    // to: a sample adds 1 to the weight sums (ShadowStats::add) and nothing
    // else, so the batch is counted without building its LightSamples.
    const bool unit_weights = primary.found && !settings_.cosine_falloff && !separate && listeners.empty();
    const bool visibility_counts = unit_weights && !occluder_distances;
    // The same with occluder distances (the shadow group's first round): a
    // sample adds 1 to the weight sums and its distance to d2min/d2max, whose
    // minimum and maximum do not depend on the order they are taken in.
    const bool distance_counts = unit_weights && occluder_distances;
    // The light points of a batch of samples first (random numbers, strata,
    // the warp: one tight loop each), then their rays; the same numbers in
    // the same order as one sample at a time.
    std::array<float, kSampleBatch> unit_s, unit_t, y_u_m, y_v_m;
    std::array<bool, kSampleBatch> visible;
    for (std::uint32_t first = 0; first < count; first += kSampleBatch) {
        const std::uint32_t batch = std::min(kSampleBatch, count - first);
        for (std::uint32_t k = 0; k < batch; ++k) {
            float u1, u2;
            rng.next_float2(u1, u2);
            const UnitPoint y_unit = strata.point(first + k, stratum_key, u1, u2);
            unit_s[k] = y_unit.s;
            unit_t[k] = y_unit.t;
        }
        if (primary.found)
            light_samplers_[0].warp(unit_s.data(), unit_t.data(), batch, y_u_m.data(), y_v_m.data());
        // Visibility only: the batch's rays in one loop, before the samples.
        const bool batch_traced = primary.found && !occluder_distances;
        if (batch_traced)
            trace_visibility_batch(primary, origin, batch, y_u_m.data(), y_v_m.data(), visible.data());
        if (distance_counts)
            trace_distance_batch(primary, origin, d1, batch, y_u_m.data(), y_v_m.data(), visible.data(),
                                 stats);
        if (visibility_counts || distance_counts) {
            stats.add_unit_weights(visible.data(), batch);
            continue;
        }
        for (std::uint32_t k = 0; k < batch; ++k) {
            LightSample sample;
            sample.y_unit = {unit_s[k], unit_t[k]};
            // The key light's visibility at the central hit (none for a thin
            // lens's background pixel, which only gathers lens rays).
            sample.has_receiver = primary.found;
            if (primary.found) {
                sample.y_u_m = y_u_m[k];
                sample.y_v_m = y_v_m[k];
                trace_key_light(primary, origin, d1, centre_falloff, occluder_distances,
                                batch_traced ? &visible[k] : nullptr, sample);
            }
            if (separate) sample.radiance = separate_radiance(primary, focus, secondary_rng, sample);
            stats.add(sample);
            for (AovAccumulator *listener : listeners) listener->add_sample(pixel_index, sample);
        }
    }
}

Renderer::CentreShadow Renderer::trace_centre_shadow(const PrimaryHit &primary) const {
    CentreShadow shadow;
    const Vec3 target = scene_.key_light().center;
    if (dot(primary.normal, target - primary.position) <= 0) {
        shadow.visible = false;  // the surface itself faces away: an attached shadow
        return shadow;
    }
    const Vec3 origin = offset_ray_origin(primary.position, primary.normal);
    const Hit hit = rays_.closest_hit(origin, target - origin, 0.0f, kShadowRayReach);
    if (hit.found) {
        shadow.visible = false;
        shadow.occluder_m = hit.distance * length(target - origin);
    }
    return shadow;
}

Renderer::SecondaryHit Renderer::trace_secondary(const PrimaryHit &primary, Vec3 direction) const {
    SecondaryHit seen;
    const Vec3 origin = offset_ray_origin(primary.position, primary.normal);
    const Hit hit = rays_.closest_hit(origin, direction, 0.0f, std::numeric_limits<float>::infinity());
    if (!hit.found) return seen;
    const Vec3 point = origin + direction * hit.distance;
    Vec3 n = normalize(hit.geometric_normal);
    n = dot(n, direction) > 0 ? -n : n;
    seen.distance_m = hit.distance;
    // Every light towards its centre ({0.5, 0.5} of the light's unit square).
    seen.radiance = shade(scene_.meshes[hit.mesh_index], point, n, origin, UnitPoint{0.5f, 0.5f}, 0);
    return seen;
}

/// World size of the pixel at the hit: the rays through the neighbouring
/// pixel centres meet the hit's tangent plane; d = sqrt(|dP/dx x dP/dy|),
/// which includes foreshortening.
float Renderer::pixel_footprint(const PrimaryHit &primary, int x, int y) const {
    const Camera &camera = scene_.camera;
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
