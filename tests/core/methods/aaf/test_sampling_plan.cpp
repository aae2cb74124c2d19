#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "aaf/core/methods/aaf/aaf_bandlimits.h"
#include "aaf/core/methods/aaf/sampling_plan.h"
#include "aaf/core/util/error.h"

using namespace aaf;

namespace {

/// sigma 0.5 m on a rectangle 16 sigma wide: untruncated, so every band-limit rule gives 0.5 m.
LightPlane untruncated_light() {
    LightPlane light = LightPlane::square(Vec3{0, 3, 0}, Vec3{0, -1, 0}, 8.0f);
    light.sigma_m = 0.5f;
    return light;
}

}  // namespace

TEST_CASE("Sampling plan follows AAF Eq. 21 on a synthetic first pass", "[aaf][plan]") {
    // Row of 12 pixels: x < 3 occluded (d2 = 1 m, 0.5 m), x in [3, 9) unoccluded but
    // within 5 px of an occluded one, x >= 9 unoccluded and too far; x = 11 background.
    const int w = 12, h = 1;
    std::vector<float> d1(w, 2.0f), d2_min(w, 0.0f), d2_max(w, 0.0f), id(w, 1.0f), size(w, 0.01f),
        spp(w, -1.0f);
    for (int x = 0; x < 3; ++x) {
        d2_min[x] = 0.5f;
        d2_max[x] = 1.0f;
    }
    id[11] = 0.0f;
    SamplingPlanInputs in{plane_view(d1.data(), w, h),     plane_view(d2_min.data(), w, h),
                          plane_view(d2_max.data(), w, h), plane_view(id.data(), w, h),
                          plane_view(size.data(), w, h),   {}};
    SamplingPlanParams params;
    plan_samples(in, untruncated_light(), AafParams{}, params, plane_view(spp.data(), w, h));
    // Hand value (see test_aaf_bandlimits): n = 4 * 49 * 0.54^2 = 57.15 -> 58 samples.
    for (int x = 0; x < 3; ++x) CHECK(spp[x] == 58.0f);
    for (int x = 3; x <= 7; ++x) CHECK(spp[x] == 58.0f);  // borrowed (distance <= 5 from x = 2)
    for (int x = 8; x < w; ++x) CHECK(spp[x] == 9.0f);    // nothing within 5 px: first pass only

    params.max_spp = 40;
    plan_samples(in, untruncated_light(), AafParams{}, params, plane_view(spp.data(), w, h));
    CHECK(spp[0] == 40.0f);
}

TEST_CASE("Sampling rate decreases with mu and stays finite near contact", "[aaf][plan]") {
    float previous = 1e30f;
    for (float mu : {4.0f, 3.0f, 2.0f, 1.5f, 1.0f}) {
        AafParams params;
        params.mu = mu;
        const float n = aaf_bandlimits(2.0f, 0.4f, 1.1f, 0.008f, 0.5f, params).samples_per_pixel;
        CHECK(n < previous);
        previous = n;
    }
    // d2max -> d1 (s2 -> 0): AAF Eq. 17 diverges, the clipped form of AAF Eq. 8 does not.
    const float contact = aaf_bandlimits(2.0f, 0.4f, 1.99999f, 0.008f, 0.5f, AafParams{}).samples_per_pixel;
    CHECK(std::isfinite(contact));
}

TEST_CASE("Sampling plan rejects bad parameters", "[aaf][plan]") {
    std::vector<float> a(4, 1.0f), out(4);
    SamplingPlanInputs in{plane_view(a.data(), 2, 2), plane_view(a.data(), 2, 2), plane_view(a.data(), 2, 2),
                          plane_view(a.data(), 2, 2), plane_view(a.data(), 2, 2), {}};
    SamplingPlanParams bad;
    bad.max_spp = 4;
    CHECK_THROWS_AS(plan_samples(in, untruncated_light(), AafParams{}, bad, plane_view(out.data(), 2, 2)),
                    Error);
    CHECK_THROWS_AS(plan_samples(in, untruncated_light(), AafParams{}, SamplingPlanParams{},
                                 plane_view(out.data(), 1, 4)),
                    Error);
}
