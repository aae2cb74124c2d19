#include "ratio_sampling.h"

#include <algorithm>
#include <cmath>

#include "aaf/trace/shading/ggx.h"
#include "aaf/trace/shading/polygon_irradiance.h"
#include "random.h"
#include "shading.h"
#include "spherical_rectangle.h"
#include "stratified_grid.h"
#include "surface_texture.h"

namespace aaf::trace {

namespace {

/// Distinguishes the ratio samples' random numbers from the AAF samples'.
constexpr std::uint64_t kRatioStream = 0x2545f4914f6cdd1dull;
/// The technique probabilities' clamp (glossy_sampling_probability).
constexpr double kMinTechniqueProbability = 0.1;

Vec3d to_double(Vec3 v) {
    return {double(v.x), double(v.y), double(v.z)};
}
Vec3 to_float(Vec3d v) {
    return {float(v.x), float(v.y), float(v.z)};
}
double luminance(Vec3 c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

}  // namespace

RectLight ratio_light(const SceneLight &light) {
    const float area_m2 = light.plane.width_m * light.plane.height_m;
    return {light.plane, light.color * (light.intensity / area_m2)};
}

double glossy_sampling_probability(const UnshadowedLight &u, bool glossy) {
    if (!glossy) return 0;
    const double total = luminance(u.total());
    // No light reaches the point: any choice gives zero; keep both techniques.
    if (!(total > 0)) return 0.5;
    return std::clamp(luminance(u.specular) / total, kMinTechniqueProbability, 1 - kMinTechniqueProbability);
}

RatioLayers trace_ratio_layers(const RayQueries &rays, const SceneDescription &scene,
                               const PrimaryHit &primary, std::size_t light_index, int samples,
                               std::uint64_t seed, std::uint64_t pixel_index) {
    RatioLayers layers;
    const Vec3 p = primary.position;
    const TexturedSurface surface = texture_surface(primary.mesh->material, p, primary.normal);
    const Material &material = surface.material;
    const Vec3 n = surface.normal;
    const Vec3 wo = normalize(scene.camera.eye - p);
    const RectLight light = ratio_light(scene.lights[light_index]);
    const SurfaceReflectance reflectance{material.albedo, material.specular, material.roughness};
    // ratio estimator Eq. 20.
    const UnshadowedLight u = rect_light_unshadowed(light, p, n, wo, reflectance);
    layers.analytic = u.total();

    const SphericalRectangle rectangle(light.plane, to_double(p));
    if (!rectangle.visible()) return layers;
    const ShadingFrame frame = ShadingFrame::from(to_double(n), to_double(wo));
    const Vec3d wo_local = frame.to_local(to_double(wo));
    const bool glossy = material.has_specular() && wo_local.z > 0;
    const double q_glossy = glossy_sampling_probability(u, glossy);
    const double alpha = double(material.roughness) * material.roughness;

    PixelRng rng(seed ^ kRatioStream, pixel_index, std::uint32_t(light_index));
    const std::uint32_t stratum_key = rng.next_u32();
    const double selection_offset = rng.next_float();
    const std::uint32_t selection_key = rng.next_u32();
    const StratifiedGrid strata{std::uint32_t(samples)};
    double shadowed[3] = {0, 0, 0}, unshadowed[3] = {0, 0, 0};
    for (int k = 0; k < samples; ++k) {
        float u1, u2;
        rng.next_float2(u1, u2);
        const UnitPoint cell = strata.point(std::uint32_t(k), stratum_key, u1, u2);
        // The technique, stratified over the pixel's samples by a randomly
        // shifted lattice over a hashed permutation of the sample index:
        // sample k draws from the glossy lobe when frac(pi(k) / N + offset) <
        // q_glossy. For each k that value is uniform, so every sample follows
        // the mixture density. The permutation matters: when N fills the grid
        // sample k's stratum is cell k, and a lattice over k itself gives each
        // technique a contiguous band of rows (an azimuth band of the lobe) that
        // no N refines, so U_N and S_N would not converge per pixel.
        const std::uint32_t order = permute_index(std::uint32_t(k), std::uint32_t(samples), selection_key);
        double selection = double(order) / samples + selection_offset;
        selection -= std::floor(selection);
        const bool from_lobe = selection < q_glossy;
        Vec3d y, wi_local;
        if (from_lobe) {
            wi_local = ggx::sample(wo_local, alpha, cell.s, cell.t);
            const Vec3d wi = frame.x * wi_local.x + frame.y * wi_local.y + frame.z * wi_local.z;
            if (!rectangle.intersect(wi, y)) continue;  // R L = 0 off the light
        } else {
            y = rectangle.sample(cell.s, cell.t);
            wi_local = frame.to_local(normalize(y - to_double(p)));
        }
        const Vec3d wi_world = normalize(y - to_double(p));
        const double cos_surface = dot(wi_world, to_double(n));
        if (!(cos_surface > 0)) continue;  // below the shading normal's horizon
        // Balance heuristic with the selection probabilities (one-sample
        // model): w_t / (q_t p_t) = 1 / sum_t' q_t' p_t'.
        const double density = (1 - q_glossy) * rectangle.pdf(y) +
                               (glossy ? q_glossy * ggx::sample_pdf(wo_local, wi_local, alpha) : 0.0);
        if (!(density > 0)) continue;
        const Vec3 brdf = evaluate_brdf(material, n, wo, to_float(wi_world));
        const bool visible = !shadow_ray_blocked(rays, primary.position, primary.normal, to_float(y));
        for (int c = 0; c < 3; ++c) {
            // ratio estimator Eq. 21-22: R L / p, with V for S_N.
            const double value = double(brdf[c]) * double(light.radiance[c]) * cos_surface / density;
            unshadowed[c] += value;
            if (visible) shadowed[c] += value;
        }
    }
    layers.shadowed =
        Vec3{float(shadowed[0] / samples), float(shadowed[1] / samples), float(shadowed[2] / samples)};
    layers.unshadowed =
        Vec3{float(unshadowed[0] / samples), float(unshadowed[1] / samples), float(unshadowed[2] / samples)};
    return layers;
}

}  // namespace aaf::trace
