#include "aaf/core/aaf_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "aaf/core/aaf_bandlimits.h"
#include "aaf/core/error.h"
#include "aaf/core/gather.h"
#include "aaf/core/light_bandlimit.h"
#include "aaf/core/occluder_fill.h"
#include "aaf/core/parallel.h"

namespace aaf {

namespace {

/// Taps stop at 3 beta, where the Gaussian weight has fallen to exp(-4.5).
constexpr float kCutoffSigmas = 3.0f;

void check_size(ConstPlaneView view, int width, int height, const char *what) {
    if (!view.valid() || view.width != width || view.height != height)
        throw Error(std::string("AAF input '") + what + "' is missing or has another size");
}

void check_inputs(const AafInputs &in, const LightPlane &light, const AafParams &params) {
    params.validate();
    light.validate();
    const int width = in.visibility.width, height = in.visibility.height;
    if (width <= 0 || height <= 0) throw Error("AAF input 'visibility' is missing or empty");
    check_size(in.d1, width, height, "d1");
    check_size(in.d2_min, width, height, "d2min");
    check_size(in.d2_max, width, height, "d2max");
    for (int c = 0; c < 3; ++c) {
        check_size(in.position[c], width, height, "position");
        check_size(in.normal[c], width, height, "normal");
    }
    check_size(in.object_id, width, height, "object_id");
    check_size(in.pixel_size, width, height, "pixel_size");
    if (params.mu_from_spp || (!params.fixed_mu && in.spp.valid())) check_size(in.spp, width, height, "spp");
}

/// beta of AAF Eq. 13 along the light's two axes at pixel (x, y), world
/// metres, or 0 where AAF does not filter (background, no occluder nearby,
/// unusable distances).
struct PixelBeta {
    float u_m = 0, v_m = 0;
};
PixelBeta pixel_beta_m(const AafInputs &in, const LightPlane &light, LightBandlimitAxes bandlimit_sigma_m,
                       const AafParams &params, const FilledOccluders &occluders, int x, int y) {
    const std::size_t i = std::size_t(y) * std::size_t(in.visibility.width) + std::size_t(x);
    const float d1 = in.d1(x, y);
    float pixel_size = in.pixel_size(x, y);
    if (params.projected_pixel && std::isfinite(pixel_size))
        pixel_size = projected_pixel_size_m(
            pixel_size, Vec3{in.normal[0](x, y), in.normal[1](x, y), in.normal[2](x, y)}, light.normal);
    const float d2_min = occluders.d2_min_m[i], d2_max = occluders.d2_max_m[i];
    if (in.object_id(x, y) == 0 || !(d1 > 0) || !(pixel_size > 0) || !std::isfinite(pixel_size) ||
        !has_occluder(d2_max))
        return {};
    if (params.fixed_beta_m > 0) return {params.fixed_beta_m, params.fixed_beta_m};
    AafParams pixel_params = params;
    if (!params.fixed_mu && in.spp.valid())  // AAF Sec. 5.2: the filter follows the samples actually taken
        pixel_params.mu =
            mu_for_samples(in.spp(x, y), d1, d2_min, d2_max, pixel_size, bandlimit_sigma_m, params);
    const AafAxisBandlimits b =
        aaf_bandlimits_axes(d1, d2_min, d2_max, pixel_size, bandlimit_sigma_m, pixel_params);
    return {b.u.beta_m, b.v.beta_m};
}

}  // namespace

GatherGuides aaf_gather_guides(const AafInputs &in, const LightPlane &light, const AafParams &params,
                               PlaneView beta_m) {
    check_inputs(in, light, params);
    if (beta_m.valid() && (beta_m.width != in.visibility.width || beta_m.height != in.visibility.height))
        throw Error("AAF output 'beta' has another size");
    // AAF Sec. 6: unoccluded pixels take the occluder distances of their neighbours.
    // Filled before the guides exist, so the search's scratch planes never coexist with them.
    const FilledOccluders occluders =
        fill_occluder_distances(in.d2_min, in.d2_max, in.object_id, params.fill_radius_px);
    GatherGuides guides;
    guides.resize(in.visibility.width, in.visibility.height);
    if (beta_m.valid())
        parallel_for_rows(guides.height, [&](int y) {
            for (int x = 0; x < guides.width; ++x) beta_m(x, y) = 0.0f;
        });
    const LightBandlimitAxes bandlimit_sigma_m = aaf_light_sigmas_m(light, params);
    // One band-limit per light axis: the Gaussian is anisotropic in the light's plane.
    const bool anisotropic = bandlimit_sigma_m.u_m != bandlimit_sigma_m.v_m;
    if (anisotropic)
        guides.inv_two_sigma_sq_v.assign(std::size_t(guides.width) * std::size_t(guides.height), 0.0f);
    const bool along_light = params.light_distance != AafLightDistance::OrthogonalProjection;
    if (along_light) {
        const std::size_t count = std::size_t(guides.width) * std::size_t(guides.height);
        guides.coord_n_m.assign(count, 0.0f);
        guides.shear_u.assign(count, 0.0f);
        guides.shear_v.assign(count, 0.0f);
        guides.inv_two_sigma_sq_n.assign(count, 0.0f);
    }
    const float variance_u_m2 = light.variance_u_m2(), variance_v_m2 = light.variance_v_m2();

    parallel_for_rows(guides.height, [&](int y) {
        for (int x = 0; x < guides.width; ++x) {
            const std::size_t i = guides.index(x, y);
            // Coordinates along the light's two tangent axes, so du^2 + dv^2 =
            // |x - x'|^2 - [n . (x - x')]^2 (AAF Eq. 12) for the orthonormal frame.
            const Vec3 p{in.position[0](x, y), in.position[1](x, y), in.position[2](x, y)};
            const float u = dot(light.axis_u, p - light.center), v = dot(light.axis_v, p - light.center);
            if (!std::isfinite(u + v)) {
                // Unusable geometry: never a tap (NaN id), never filtered.
                guides.object_id[i] = std::numeric_limits<float>::quiet_NaN();
                continue;
            }
            guides.coord_u_m[i] = u;
            guides.coord_v_m[i] = v;
            // The spread of the slide's direction over the light, per unit dn (below).
            float spread_u_sq = 0, spread_v_sq = 0;
            if (along_light) {
                // Delta_eff = Delta - l (n . Delta) / (n . l), l the unit direction to the
                // light's centre: the tap slid along l onto the centre's plane parallel to
                // the light (AAF Fig. 2's geometry), of which AAF Eq. 12 is the case l = n.
                const Vec3 to_light = light.center - p;
                const float distance = length(to_light);
                const Vec3 receiver_normal{in.normal[0](x, y), in.normal[1](x, y), in.normal[2](x, y)};
                const float receiver_length = length(receiver_normal);
                // Guarded: AAF Eq. 12's projection (no shear) wherever it does not collapse the receiver.
                const bool projection_holds = params.light_distance == AafLightDistance::Guarded &&
                                              receiver_length > 0 &&
                                              std::fabs(dot(receiver_normal, light.normal)) >=
                                                  kDegenerateProjectionCos * receiver_length;
                if (distance > 0 && !projection_holds) {
                    const Vec3 l = to_light / distance;
                    // Nearly edge-on (|n . l| < 0.05, 87 degrees) the shear is held at 20.
                    constexpr float kMinCos = 0.05f;
                    const float cos_light = dot(l, light.normal);
                    const float denominator =
                        std::fabs(cos_light) < kMinCos ? std::copysign(kMinCos, cos_light) : cos_light;
                    guides.shear_u[i] = dot(l, light.axis_u) / denominator;
                    guides.shear_v[i] = dot(l, light.axis_v) / denominator;
                    // The slide is along the ray to the light's centre; towards a light
                    // point y it differs by (y - c) / d1 per unit dn, so over the light's
                    // profile the squared offset grows by dn^2 var(y) / d1^2 per axis.
                    const float d1 = std::fabs(dot(light.normal, p - light.center));
                    spread_u_sq = variance_u_m2 / (d1 * d1);
                    spread_v_sq = variance_v_m2 / (d1 * d1);
                }
                guides.coord_n_m[i] = dot(light.normal, p - light.center);
            }
            const Vec3 n{in.normal[0](x, y), in.normal[1](x, y), in.normal[2](x, y)};
            const float len = length(n);
            const Vec3 unit = (len > 0 && std::isfinite(len)) ? n / len : Vec3{};
            guides.normal_x[i] = unit.x;
            guides.normal_y[i] = unit.y;
            guides.normal_z[i] = unit.z;
            guides.object_id[i] = in.object_id(x, y);

            const PixelBeta beta = pixel_beta_m(in, light, bandlimit_sigma_m, params, occluders, x, y);
            if (!(beta.u_m > 0) || !(beta.v_m > 0) || !std::isfinite(beta.u_m) || !std::isfinite(beta.v_m))
                continue;
            // beta is in world metres; the reach in pixels follows from the pixel's footprint.
            const float widest = std::max(beta.u_m, beta.v_m);
            const float radius = std::min(std::ceil(kCutoffSigmas * widest / in.pixel_size(x, y)),
                                          float(params.max_radius_px));
            // The beta output: the isotropic width of the same area, sqrt(beta_u beta_v).
            if (beta_m.valid()) beta_m(x, y) = anisotropic ? std::sqrt(beta.u_m * beta.v_m) : beta.u_m;
            // A beta below ~1e-19 m (pixel.size near 0) squares to 0 or a
            // denormal: the largest float instead of inf keeps the centre tap's
            // exponent 0 * that = 0 (weight 1), where inf would give 0 * inf = NaN.
            auto inv_two_sigma_sq = [](float b) {
                return std::min(1.0f / (2.0f * b * b), std::numeric_limits<float>::max());
            };
            guides.inv_two_sigma_sq[i] = inv_two_sigma_sq(beta.u_m);
            if (anisotropic) guides.inv_two_sigma_sq_v[i] = inv_two_sigma_sq(beta.v_m);
            if (along_light) {
                // Finite, so that the centre tap's dn = 0 gives 0, never 0 x inf.
                const float weight_n =
                    spread_u_sq * guides.inv_two_sigma_sq[i] +
                    spread_v_sq * (anisotropic ? guides.inv_two_sigma_sq_v[i] : guides.inv_two_sigma_sq[i]);
                guides.inv_two_sigma_sq_n[i] =
                    std::isfinite(weight_n) ? weight_n : std::numeric_limits<float>::max();
            }
            guides.radius_px[i] = int(radius);
        }
    });
    return guides;
}

GatherSettings aaf_gather_settings(const AafParams &params) {
    GatherSettings settings;
    settings.normal_threshold_deg = params.normal_threshold_deg;
    settings.mode = params.mode == AafFilterMode::Separable ? GatherMode::Separable : GatherMode::Full2D;
    settings.symmetric_borders = params.symmetric_borders;
    return settings;
}

void aaf_filter(const AafInputs &in, const LightPlane &light, const AafParams &params,
                const AafOutputs &out) {
    check_inputs(in, light, params);
    const int width = in.visibility.width, height = in.visibility.height;
    if (!out.filtered_visibility.valid() || out.filtered_visibility.width != width ||
        out.filtered_visibility.height != height)
        throw Error("AAF output 'filtered visibility' is missing or has another size");

    // beta goes straight to its output, and the visibility is filtered in its
    // output's plane: no frame-sized copy beside the guides (peak memory).
    const GatherGuides guides = aaf_gather_guides(in, light, params, out.beta_m);

    // Non-finite visibility (a renderer's NaN) is read as 0, so it cannot spread through the filter.
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const float v = in.visibility(x, y);
            out.filtered_visibility(x, y) = std::isfinite(v) ? v : 0.0f;
        }
    });
    gather(guides, aaf_gather_settings(params), {out.filtered_visibility}, {out.filtered_visibility});
}

}  // namespace aaf
