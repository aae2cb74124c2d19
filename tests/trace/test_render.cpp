#include <catch2/catch.hpp>

#include <cmath>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/trace/render.h"

using namespace aaf;

namespace {

AovSet render_small(int spp, std::uint64_t seed, int threads) {
    trace::RenderSettings settings;
    settings.width = 48;
    settings.height = 36;
    settings.spp = spp;
    settings.seed = seed;
    settings.threads = threads;
    return trace::render_builtin("grids", settings);
}

}  // namespace

TEST_CASE("Render is identical for any thread count and depends on the seed", "[trace]") {
    const AovSet one = render_small(9, 3, 1);
    const AovSet two = render_small(9, 3, 2);
    const AovSet reseeded = render_small(9, 4, 2);
    REQUIRE(one.channel_names() == two.channel_names());
    for (std::size_t c = 0; c < one.channel_names().size(); ++c) CHECK(one.plane(c) == two.plane(c));
    CHECK(one.channel("shadow.V").data != reseeded.channel("shadow.V").data);
    bool any_different = false;
    for (std::size_t i = 0; i < one.pixel_count(); ++i)
        any_different =
            any_different || one.channel("shadow.V").data[i] != reseeded.channel("shadow.V").data[i];
    CHECK(any_different);
}

TEST_CASE("Render writes every AAF AOV with consistent values", "[trace]") {
    const AovSet aovs = render_small(16, 1, 0);
    const ChannelMap map;
    CHECK(map.missing_inputs(method_table().front(), aovs).empty());
    const LightPlane light = read_light_attributes(aovs);
    CHECK(light.sigma_m == Approx(0.5f * light.width_m));

    int penumbra = 0, lit = 0;
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            if (aovs.channel("id.object")(x, y) == 0) continue;
            const float v = aovs.channel("shadow.V")(x, y);
            const float d1 = aovs.channel("shadow.d1")(x, y);
            const float d2_min = aovs.channel("shadow.d2min")(x, y),
                        d2_max = aovs.channel("shadow.d2max")(x, y);
            REQUIRE(v >= 0.0f);
            REQUIRE(v <= 1.0f);
            if (d2_max == 0) {
                CHECK(v == 1.0f);  // no occluder: fully lit, exactly
                ++lit;
            } else {
                CHECK(d2_min > 0);
                CHECK(d2_min <= d2_max);
                CHECK(d2_max <= d1 + 1e-3f);
                if (v > 0 && v < 1) ++penumbra;
            }
            // AAF Eq. 1: beauty = r(x) * visibility, per channel.
            for (const char *c : {"R", "G", "B"})
                CHECK(aovs.channel(c)(x, y) == aovs.channel(std::string("unshadowed.") + c)(x, y) * v);
            CHECK(aovs.channel("pixel.spp")(x, y) == 16.0f);
            CHECK(aovs.channel("pixel.size")(x, y) > 0.0f);
            CHECK(d1 == Approx(light.plane_distance_m({aovs.channel("P.X")(x, y), aovs.channel("P.Y")(x, y),
                                                       aovs.channel("P.Z")(x, y)})));
        }
    CHECK(penumbra > 50);
    CHECK(lit > 0);
}

TEST_CASE("Pixel size on the ground matches the pinhole camera's footprint", "[trace]") {
    // Camera: eye (0, 4.2, 5.2) looking at (0, 0.2, 0), 45 degree vertical field of view, 480 rows.
    // A pixel spans s = 2 tan(22.5 deg) / 480 at unit depth; seen at angle theta off the axis it
    // subtends a solid angle s^2 cos^3(theta), which lands on the ground at distance r with
    // incidence cosine cos_i as an area s^2 cos^3(theta) r^2 / cos_i; d is its square root.
    trace::RenderSettings settings;
    settings.width = 640;
    settings.height = 480;
    settings.spp = 1;
    const AovSet aovs = trace::render_builtin("grids", settings);
    const int x = 320, y = 470;  // bottom centre: ground in front of the lattices
    REQUIRE(aovs.channel("id.object")(x, y) == 1.0f);
    const Vec3 eye{0, 4.2f, 5.2f};
    const Vec3 p{aovs.channel("P.X")(x, y), aovs.channel("P.Y")(x, y), aovs.channel("P.Z")(x, y)};
    const Vec3 forward = normalize(Vec3{0, 0.2f, 0} - eye);
    const Vec3 to_p = p - eye;
    const float r = length(to_p);
    const float s = 2.0f * std::tan(22.5f * 3.14159265f / 180.0f) / 480.0f;
    const float cos_theta = dot(to_p, forward) / r;
    const float cos_incidence = std::fabs(to_p.y) / r;
    const float expected = std::sqrt(s * s * cos_theta * cos_theta * cos_theta * r * r / cos_incidence);
    CHECK(aovs.channel("pixel.size")(x, y) == Approx(expected).epsilon(0.03));
}

TEST_CASE("Render rejects bad settings and unknown scenes", "[trace]") {
    trace::RenderSettings settings;
    settings.width = 0;
    CHECK_THROWS_AS(trace::render_builtin("grids", settings), Error);
    settings = {};
    settings.spp = 0;
    CHECK_THROWS_AS(trace::render_builtin("grids", settings), Error);
    CHECK_THROWS_WITH(trace::render_builtin("nope", trace::RenderSettings{}), Catch::Contains("grids"));
}

TEST_CASE("Adaptive sampling follows the plan, capped, and is thread-count independent",
          "[trace][adaptive]") {
    trace::RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.adaptive = true;
    settings.max_spp = 60;
    settings.threads = 1;
    const AovSet one = trace::render_builtin("grids", settings);
    settings.threads = 2;
    const AovSet two = trace::render_builtin("grids", settings);
    for (std::size_t c = 0; c < one.channel_names().size(); ++c) CHECK(one.plane(c) == two.plane(c));

    int above_first_pass = 0;
    for (int y = 0; y < one.height(); ++y)
        for (int x = 0; x < one.width(); ++x) {
            if (one.channel("id.object")(x, y) == 0) continue;
            const float spp = one.channel("pixel.spp")(x, y);
            REQUIRE(spp >= 9.0f);
            REQUIRE(spp <= 60.0f);
            if (spp > 9.0f) ++above_first_pass;
            // Pixels with no occluder anywhere near keep the first pass only.
            if (spp > 9.0f) CHECK(one.channel("shadow.d1")(x, y) > 0.0f);
        }
    CHECK(above_first_pass > 100);
}

TEST_CASE("Cosine falloff keeps visibility in [0, 1] and exactly 1 when unoccluded", "[trace][falloff]") {
    trace::RenderSettings settings;
    settings.width = 48;
    settings.height = 36;
    settings.spp = 16;
    settings.cosine_falloff = true;
    const AovSet aovs = trace::render_builtin("grids", settings);
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            const float v = aovs.channel("shadow.V")(x, y);
            REQUIRE(v >= 0.0f);
            REQUIRE(v <= 1.0f);
            if (aovs.channel("shadow.d2max")(x, y) == 0) CHECK(v == 1.0f);
        }
}

TEST_CASE("Shadow rays from the ground never hit the ground itself (no acne)", "[trace]") {
    // Every occluder of a ground pixel is a lattice bar, the lowest of whose
    // undersides lies 0.335 m above the ground: d2 <= d1 - 0.335. A self-hit
    // would report d2 close to d1.
    trace::RenderSettings settings;
    settings.width = 80;
    settings.height = 60;
    settings.spp = 64;
    const AovSet aovs = trace::render_builtin("grids", settings);
    int ground = 0;
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            if (aovs.channel("id.object")(x, y) != 1.0f) continue;
            ++ground;
            const float d2_max = aovs.channel("shadow.d2max")(x, y);
            if (d2_max > 0)
                REQUIRE(d2_max <= aovs.channel("shadow.d1")(x, y) - 0.33f);
            else
                REQUIRE(aovs.channel("shadow.V")(x, y) == 1.0f);
        }
    CHECK(ground > 1000);
}
