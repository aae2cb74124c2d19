// AAF's guides per pixel (aaf_guide_rows.h, Google Highway runtime
// dispatch): on every instruction set the build carries, aaf_gather_guides()
// gives the bits of the scalar definitions it vectorises (the per-pixel loop
// below, written with aaf_bandlimits.h's scalar functions), for every
// parameter that changes its path.
#include <hwy/targets.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "../../../unpinned_instruction_set.h"
#include "aaf/core/methods/aaf/aaf_bandlimits.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/methods/aaf/aaf_guide_rows.h"
#include "aaf/core/methods/aaf/occluder_fill.h"
#include "aaf/core/util/frame_allocator.h"

using namespace aaf;

namespace {

/// Planes of one AAF input frame with every case the guides branch on:
/// unusable positions (NaN, inf), zero and NaN normals, background (id 0),
/// unoccluded pixels (d2max 0, filled from neighbours or not), non-positive
/// d1, zero, tiny and infinite pixel sizes, and sample counts below the
/// floor mu's rate, between, and beyond the largest mu's.
struct Frame {
    int width = 37, height = 11;  // 37: a partial vector at each row's end for every lane count
    std::vector<float> visibility, d1, d2_min, d2_max, px, py, pz, nx, ny, nz, id, pixel_size, spp;

    Frame() {
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        const std::size_t n = std::size_t(width) * height;
        for (std::vector<float> *p :
             {&visibility, &d1, &d2_min, &d2_max, &px, &py, &pz, &nx, &ny, &nz, &id, &pixel_size, &spp})
            p->resize(n);
        const float nan = std::numeric_limits<float>::quiet_NaN(),
                    inf = std::numeric_limits<float>::infinity();
        for (std::size_t i = 0; i < n; ++i) {
            visibility[i] = unit(rng);
            px[i] = -1.0f + 2.0f * unit(rng);
            py[i] = 0.2f * unit(rng);
            pz[i] = -1.0f + 2.0f * unit(rng);
            const float tilt = 1.6f * unit(rng);
            nx[i] = std::sin(tilt) * 1.5f;  // not unit: the guides normalise
            ny[i] = std::cos(tilt) * 1.5f;
            nz[i] = 0.1f * unit(rng);
            id[i] = unit(rng) < 0.1f ? 0.0f : (unit(rng) < 0.5f ? 1.0f : 2.0f);
            d1[i] = 1.0f + unit(rng);
            const bool occluded = unit(rng) < 0.5f;
            d2_max[i] = occluded ? d1[i] * (0.2f + 0.8f * unit(rng)) : 0.0f;
            d2_min[i] = occluded ? d2_max[i] * (0.3f + 0.7f * unit(rng)) : 0.0f;
            pixel_size[i] = 0.002f + 0.01f * unit(rng);
            spp[i] = std::pow(10.0f, 4.0f * unit(rng));
            switch (int(unit(rng) * 40.0f)) {
                case 0:
                    px[i] = nan;
                    break;
                case 1:
                    pz[i] = inf;
                    break;
                case 2:
                    nx[i] = ny[i] = nz[i] = 0.0f;
                    break;
                case 3:
                    ny[i] = nan;
                    break;
                case 4:
                    d1[i] = -0.5f;
                    break;
                case 5:
                    pixel_size[i] = 0.0f;
                    break;
                case 6:
                    pixel_size[i] = 1e-30f;
                    break;
                case 7:
                    pixel_size[i] = inf;
                    break;
                case 8:
                    d2_max[i] = inf;
                    break;
                case 9:
                    spp[i] = 1e9f;
                    break;
                case 10:
                    d2_min[i] = 0.0f;
                    break;
                case 11:
                    nx[i] = 0.0f;
                    ny[i] = 0.01f;
                    nz[i] = 1.0f;
                    break;  // edge-on to the light
                default:
                    break;
            }
        }
    }
    AafInputs inputs(bool with_spp) const {
        auto view = [&](const std::vector<float> &p) { return plane_view(p.data(), width, height); };
        AafInputs in;
        in.visibility = view(visibility);
        in.d1 = view(d1);
        in.d2_min = view(d2_min);
        in.d2_max = view(d2_max);
        in.position = {view(px), view(py), view(pz)};
        in.normal = {view(nx), view(ny), view(nz)};
        in.object_id = view(id);
        in.pixel_size = view(pixel_size);
        if (with_spp) in.spp = view(spp);
        return in;
    }
};

/// A 0.6 x 0.3 m light above the frame, tilted about its u axis.
LightPlane tilted_light() {
    LightPlane light;
    const float a = 0.3f;
    light.center = {0.1f, 2.0f, -0.2f};
    light.normal = {0.0f, -std::cos(a), std::sin(a)};
    light.axis_u = {1.0f, 0.0f, 0.0f};
    light.axis_v = {0.0f, std::sin(a), std::cos(a)};
    light.width_m = 0.6f;
    light.height_m = 0.3f;
    light.sigma_m = 0.3f;
    return light;
}

/// The scalar definition the SIMD rows replace (aaf_filter.cpp before them):
/// beta of AAF Eq. 13 along the light's axes at pixel i, 0 where AAF does not filter.
struct PixelBeta {
    float u_m = 0, v_m = 0;
};
/// How often mu_for_samples() kept the floor mu, returned its largest mu (1e4), or bisected.
struct MuOutcomes {
    int at_floor = 0, at_max = 0, bisected = 0;
};
PixelBeta reference_beta_m(const AafInputs &in, const LightPlane &light, LightBandlimitAxes sigma,
                           const AafParams &params, const FilledOccluders &occluders, int x, int y,
                           MuOutcomes &outcomes) {
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
    if (!params.fixed_mu && in.spp.valid()) {
        pixel_params.mu = mu_for_samples(in.spp(x, y), d1, d2_min, d2_max, pixel_size, sigma, params);
        ++(pixel_params.mu == params.mu ? outcomes.at_floor
           : pixel_params.mu == 1e4f    ? outcomes.at_max
                                        : outcomes.bisected);
    }
    const AafAxisBandlimits b = aaf_bandlimits_axes(d1, d2_min, d2_max, pixel_size, sigma, pixel_params);
    return {b.u.beta_m, b.v.beta_m};
}

GatherGuides reference_guides(const AafInputs &in, const LightPlane &light, const AafParams &params,
                              std::vector<float> &beta_m, MuOutcomes &outcomes) {
    GatherGuides guides;
    guides.resize(in.visibility.width, in.visibility.height);
    const std::size_t count = std::size_t(guides.width) * std::size_t(guides.height);
    beta_m.assign(count, 0.0f);
    const FilledOccluders occluders =
        fill_occluder_distances(in.d2_min, in.d2_max, in.object_id, params.fill_radius_px);
    const LightBandlimitAxes sigma = aaf_light_sigmas_m(light, params);
    const bool anisotropic = sigma.u_m != sigma.v_m;
    if (anisotropic) guides.inv_two_sigma_sq_v.assign(count, 0.0f);
    const bool along_light = params.light_distance != AafLightDistance::OrthogonalProjection;
    if (along_light)
        for (FramePlane<float> *p :
             {&guides.coord_n_m, &guides.shear_u, &guides.shear_v, &guides.inv_two_sigma_sq_n})
            p->assign(count, 0.0f);
    const float variance_u_m2 = light.variance_u_m2(), variance_v_m2 = light.variance_v_m2();
    for (int y = 0; y < guides.height; ++y)
        for (int x = 0; x < guides.width; ++x) {
            const std::size_t i = guides.index(x, y);
            const Vec3 p{in.position[0](x, y), in.position[1](x, y), in.position[2](x, y)};
            const float u = dot(light.axis_u, p - light.center), v = dot(light.axis_v, p - light.center);
            if (!std::isfinite(u + v)) {
                guides.object_id[i] = std::numeric_limits<float>::quiet_NaN();
                continue;
            }
            guides.coord_u_m[i] = u;
            guides.coord_v_m[i] = v;
            float spread_u_sq = 0, spread_v_sq = 0;
            const Vec3 n{in.normal[0](x, y), in.normal[1](x, y), in.normal[2](x, y)};
            if (along_light) {
                const Vec3 to_light = light.center - p;
                const float distance = length(to_light);
                const float receiver_length = length(n);
                const bool projection_holds =
                    params.light_distance == AafLightDistance::Guarded && receiver_length > 0 &&
                    std::fabs(dot(n, light.normal)) >= kDegenerateProjectionCos * receiver_length;
                if (distance > 0 && !projection_holds) {
                    const Vec3 l = to_light / distance;
                    const float cos_light = dot(l, light.normal);
                    const float denominator =
                        std::fabs(cos_light) < 0.05f ? std::copysign(0.05f, cos_light) : cos_light;
                    guides.shear_u[i] = dot(l, light.axis_u) / denominator;
                    guides.shear_v[i] = dot(l, light.axis_v) / denominator;
                    const float d1 = std::fabs(dot(light.normal, p - light.center));
                    spread_u_sq = variance_u_m2 / (d1 * d1);
                    spread_v_sq = variance_v_m2 / (d1 * d1);
                }
                guides.coord_n_m[i] = dot(light.normal, p - light.center);
            }
            const float len = length(n);
            const Vec3 unit = (len > 0 && std::isfinite(len)) ? n / len : Vec3{};
            guides.normal_x[i] = unit.x;
            guides.normal_y[i] = unit.y;
            guides.normal_z[i] = unit.z;
            guides.object_id[i] = in.object_id(x, y);
            const PixelBeta beta = reference_beta_m(in, light, sigma, params, occluders, x, y, outcomes);
            if (!(beta.u_m > 0) || !(beta.v_m > 0) || !std::isfinite(beta.u_m) || !std::isfinite(beta.v_m))
                continue;
            const float widest = std::max(beta.u_m, beta.v_m);
            const float radius =
                std::min(std::ceil(3.0f * widest / in.pixel_size(x, y)), float(params.max_radius_px));
            beta_m[i] = anisotropic ? std::sqrt(beta.u_m * beta.v_m) : beta.u_m;
            auto inv_two_sigma_sq = [](float b) {
                return std::min(1.0f / (2.0f * b * b), std::numeric_limits<float>::max());
            };
            guides.inv_two_sigma_sq[i] = inv_two_sigma_sq(beta.u_m);
            if (anisotropic) guides.inv_two_sigma_sq_v[i] = inv_two_sigma_sq(beta.v_m);
            if (along_light) {
                const float weight_n =
                    spread_u_sq * guides.inv_two_sigma_sq[i] +
                    spread_v_sq * (anisotropic ? guides.inv_two_sigma_sq_v[i] : guides.inv_two_sigma_sq[i]);
                guides.inv_two_sigma_sq_n[i] =
                    std::isfinite(weight_n) ? weight_n : std::numeric_limits<float>::max();
            }
            guides.radius_px[i] = int(radius);
        }
    return guides;
}

template <typename A, typename B>
bool same_bits(const A &a, const B &b) {
    // memcmp may not be given the null data() of empty planes (not allocated for these parameters).
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

/// Fills frame blocks of `count` numbers with NaN and frees them, so that the
/// planes the guides then take from the allocator (sized without zero-filling)
/// hold NaN (as radii, a huge number) wherever they would not be written.
void poison_frame_memory(std::size_t count) {
    std::vector<FramePlane<float>> planes(32);
    for (FramePlane<float> &plane : planes) plane.assign(count, std::numeric_limits<float>::quiet_NaN());
}

}  // namespace

TEST_CASE("AAF guides: every instruction set gives the scalar definition's bits", "[aaf][simd]") {
    const aaf_test::UnpinnedInstructionSet every_target;  // the test walks Highway's targets itself
    const Frame frame;
    const LightPlane light = tilted_light();
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    REQUIRE(!targets.empty());
    for (const AafLightDistance distance :
         {AafLightDistance::AlongLightDirection, AafLightDistance::OrthogonalProjection,
          AafLightDistance::Guarded})
        for (const AafLightAxes axes : {AafLightAxes::PerAxis, AafLightAxes::Shortest})
            for (const bool projected : {false, true})
                for (const bool with_spp : {false, true})
                    for (const float fixed_beta_m : {0.0f, 0.01f}) {
                        AafParams params;
                        params.light_distance = distance;
                        params.light_axes = axes;
                        params.projected_pixel = projected;
                        params.fixed_beta_m = fixed_beta_m;
                        params.max_radius_px = 9;  // some pixels reach it
                        const AafInputs in = frame.inputs(with_spp);
                        std::vector<float> expected_beta;
                        MuOutcomes mu_outcomes;
                        const GatherGuides expected =
                            reference_guides(in, light, params, expected_beta, mu_outcomes);
                        std::set<std::string> names;
                        int filtered = 0;
                        for (const std::int64_t target : targets) {
                            hwy::SetSupportedTargetsForTest(target);
                            names.insert(detail::aaf_guide_row_target());
                            // NaN beforehand: every pixel's beta must be written.
                            std::vector<float> beta(frame.d1.size(), std::numeric_limits<float>::quiet_NaN());
                            poison_frame_memory(frame.d1.size());
                            const GatherGuides g = aaf_gather_guides(
                                in, light, params, plane_view(beta.data(), frame.width, frame.height));
                            INFO("target " << hwy::TargetName(target) << ", light distance " << int(distance)
                                           << ", axes " << to_string(axes) << ", projected " << projected
                                           << ", spp " << with_spp << ", fixed beta " << fixed_beta_m);
                            CHECK(same_bits(g.coord_u_m, expected.coord_u_m));
                            CHECK(same_bits(g.coord_v_m, expected.coord_v_m));
                            CHECK(same_bits(g.normal_x, expected.normal_x));
                            CHECK(same_bits(g.normal_y, expected.normal_y));
                            CHECK(same_bits(g.normal_z, expected.normal_z));
                            CHECK(same_bits(g.object_id, expected.object_id));
                            CHECK(same_bits(g.inv_two_sigma_sq, expected.inv_two_sigma_sq));
                            CHECK(same_bits(g.inv_two_sigma_sq_v, expected.inv_two_sigma_sq_v));
                            CHECK(same_bits(g.coord_n_m, expected.coord_n_m));
                            CHECK(same_bits(g.shear_u, expected.shear_u));
                            CHECK(same_bits(g.shear_v, expected.shear_v));
                            CHECK(same_bits(g.inv_two_sigma_sq_n, expected.inv_two_sigma_sq_n));
                            CHECK(g.radius_px == expected.radius_px);
                            CHECK(same_bits(beta, expected_beta));
                            // The same into a view whose pixels are not adjacent (every other float).
                            std::vector<float> interleaved(2 * beta.size(),
                                                           std::numeric_limits<float>::quiet_NaN());
                            aaf_gather_guides(in, light, params,
                                              PlaneView(interleaved.data(), frame.width, frame.height, 2,
                                                        2 * std::ptrdiff_t(frame.width)));
                            std::vector<float> every_other(beta.size());
                            for (std::size_t i = 0; i < beta.size(); ++i) every_other[i] = interleaved[2 * i];
                            CHECK(same_bits(every_other, expected_beta));
                            filtered =
                                int(std::count_if(beta.begin(), beta.end(), [](float b) { return b > 0; }));
                        }
                        hwy::SetSupportedTargetsForTest(0);
                        // The frame exercises the filter: a good share of its pixels get a beta.
                        CHECK(filtered > int(frame.d1.size()) / 5);
                        // With the spp input, mu_for_samples' three outcomes all occur.
                        if (with_spp && fixed_beta_m == 0) {
                            CHECK(mu_outcomes.at_floor > 0);
                            CHECK(mu_outcomes.bisected > 0);
                            CHECK(mu_outcomes.at_max > 0);
                        }
                        // Dispatch really switched: as many kernels ran as targets were offered.
                        CHECK(names.size() == targets.size());
                    }
}
