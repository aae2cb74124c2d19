#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/trace/render.h"
#include "scene_description.h"
#include "scene_file.h"

using namespace aaf;

namespace {

AovSet render_small(int spp, std::uint64_t seed, int threads) {
    trace::RenderSettings settings;
    settings.width = 48;
    settings.height = 36;
    settings.spp = spp;
    settings.seed = seed;
    settings.threads = threads;
    return trace::render_scene("grids", settings);
}

/// The `index`-th channel of `role`, named by the AOV contract.
ConstPlaneView channel(const AovSet &aovs, Role role, std::size_t index = 0) {
    return aovs.channel(role_info(role).channels.at(index));
}

Vec3 position(const AovSet &aovs, int x, int y) {
    return {channel(aovs, Role::Position, 0)(x, y), channel(aovs, Role::Position, 1)(x, y),
            channel(aovs, Role::Position, 2)(x, y)};
}

/// The stored plane of the channel called `name`.
const std::vector<float> &plane(const AovSet &aovs, const std::string &name) {
    const auto &names = aovs.channel_names();
    return aovs.plane(std::size_t(std::find(names.begin(), names.end(), name) - names.begin()));
}

bool same_channels(const AovSet &a, const AovSet &b) {
    if (a.channel_names() != b.channel_names()) return false;
    for (std::size_t c = 0; c < a.channel_names().size(); ++c)
        if (a.plane(c) != b.plane(c)) return false;
    return true;
}

}  // namespace

TEST_CASE("Render is bit-identical for any thread count", "[trace]") {
    const AovSet one = render_small(9, 3, 1);
    CHECK(same_channels(one, render_small(9, 3, 4)));
    CHECK(same_channels(one, render_small(9, 3, 0)));
}

TEST_CASE("Render depends on the seed and on nothing else", "[trace]") {
    const AovSet first = render_small(9, 3, 2);
    const AovSet again = render_small(9, 3, 2);
    const AovSet reseeded = render_small(9, 4, 2);
    CHECK(same_channels(first, again));
    const ConstPlaneView v = channel(first, Role::Visibility),
                         v_reseeded = channel(reseeded, Role::Visibility);
    int different = 0;
    for (int y = 0; y < first.height(); ++y)
        for (int x = 0; x < first.width(); ++x) different += v(x, y) != v_reseeded(x, y);
    CHECK(different > 20);
    // Only the shadow noise changes: the primary hits are the same.
    for (Role role : {Role::Position, Role::Unshadowed, Role::PixelSize})
        for (const std::string &name : role_info(role).channels)
            CHECK(plane(first, name) == plane(reseeded, name));
}

TEST_CASE("Render writes every AAF AOV with consistent values", "[trace]") {
    const AovSet aovs = render_small(16, 1, 0);
    const ChannelMap map;
    for (const MethodInputs &method : method_table()) CHECK(map.missing_inputs(method, aovs).empty());
    const LightPlane light = read_light_attributes(aovs);
    CHECK(light.sigma_m == Approx(0.5f * light.width_m));
    CHECK(std::get<std::string>(aovs.attributes.at(attr::kScene)) == "grids");
    CHECK(std::get<int>(aovs.attributes.at(attr::kSeed)) == 1);
    CHECK(std::get<int>(aovs.attributes.at(attr::kSpp)) == 16);

    const ConstPlaneView v = channel(aovs, Role::Visibility), d1 = channel(aovs, Role::D1),
                         d2_min = channel(aovs, Role::D2Min), d2_max = channel(aovs, Role::D2Max),
                         id = channel(aovs, Role::ObjectId);
    int penumbra = 0, lit = 0;
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            const float object = id(x, y);
            REQUIRE((object == 0 || object == 1 || object == 2 || object == 3 || object == 4));
            if (object == 0) continue;
            REQUIRE(v(x, y) >= 0.0f);
            REQUIRE(v(x, y) <= 1.0f);
            if (d2_max(x, y) == 0) {
                CHECK(v(x, y) == 1.0f);  // no occluder: fully lit, exactly
                CHECK(d2_min(x, y) == 0);
                ++lit;
            } else {
                CHECK(d2_min(x, y) > 0);
                CHECK(d2_min(x, y) <= d2_max(x, y));
                CHECK(d2_max(x, y) <= d1(x, y) + 1e-4f);
                if (v(x, y) > 0 && v(x, y) < 1) ++penumbra;
            }
            // AAF Eq. 1: beauty = r(x) * visibility, per channel, exactly.
            for (std::size_t c = 0; c < 3; ++c)
                CHECK(channel(aovs, Role::Beauty, c)(x, y) ==
                      channel(aovs, Role::Unshadowed, c)(x, y) * v(x, y));
            const Vec3 n{channel(aovs, Role::Normal, 0)(x, y), channel(aovs, Role::Normal, 1)(x, y),
                         channel(aovs, Role::Normal, 2)(x, y)};
            CHECK(length(n) == Approx(1.0f).epsilon(1e-5));
            CHECK(channel(aovs, Role::SamplesPerPixel)(x, y) == 16.0f);
            CHECK(channel(aovs, Role::PixelSize)(x, y) > 0.0f);
            CHECK(d1(x, y) == Approx(light.plane_distance_m(position(aovs, x, y))));
        }
    CHECK(penumbra > 50);
    CHECK(lit > 0);
}

TEST_CASE("Ground far outside every lattice's shadow is fully lit", "[trace]") {
    // Lattice points lie within 1.2 sqrt(2) = 1.70 m of the vertical axis, at
    // most 1.3 m up; light points within 0.5 sqrt(2) = 0.71 m of it, 3 m up.
    // A shadow ray from the ground through a lattice point therefore leaves
    // the ground within 0.71 + (1.70 + 0.71) * 3 / (3 - 1.3) = 4.96 m of the
    // axis: ground points farther out see the whole light.
    const AovSet aovs = render_small(16, 1, 2);
    const ConstPlaneView id = channel(aovs, Role::ObjectId);
    int far_ground = 0;
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            REQUIRE(id(x, y) > 0);  // the ground fills the view behind the lattices
            const Vec3 p = position(aovs, x, y);
            if (id(x, y) != 1 || std::hypot(p.x, p.z) < 5.0f) continue;
            ++far_ground;
            CHECK(channel(aovs, Role::Visibility)(x, y) == 1.0f);
            CHECK(channel(aovs, Role::D2Max)(x, y) == 0.0f);
        }
    CHECK(far_ground > 50);
}

TEST_CASE("Pixel size on the ground matches the pinhole camera's footprint", "[trace]") {
    // The camera chosen for grids: eye (0, 4.2, 5.2) looking at (0, 0.2, 0),
    // 45 degree vertical field of view, here with 480 rows.
    const Vec3 eye{0, 4.2f, 5.2f}, target{0, 0.2f, 0};
    const float fov_y_deg = 45.0f;
    const trace::Camera camera = trace::load_scene_file(trace::resolve_scene("grids"), 640, 480).camera;
    REQUIRE(camera.eye.y == eye.y);
    REQUIRE(camera.eye.z == eye.z);
    REQUIRE(camera.tan_half_fov_y == Approx(std::tan(0.5f * fov_y_deg * 3.14159265f / 180.0f)));

    // A pixel spans s = 2 tan(22.5 deg) / 480 at unit depth; seen at angle theta off the axis it
    // subtends a solid angle s^2 cos^3(theta), which lands on the ground at distance r with
    // incidence cosine cos_i as an area s^2 cos^3(theta) r^2 / cos_i; d is its square root.
    trace::RenderSettings settings;
    settings.width = 640;
    settings.height = 480;
    settings.spp = 1;
    const AovSet aovs = trace::render_scene("grids", settings);
    // The image centre shows a lattice: take the ground straight below it
    // (in front of the lattices) and above it (behind them, seen more obliquely).
    for (int y : {470, 20}) {
        const int x = 320;
        INFO("row " << y);
        REQUIRE(channel(aovs, Role::ObjectId)(x, y) == 1.0f);
        const Vec3 to_p = position(aovs, x, y) - eye;
        const float r = length(to_p);
        const float s = 2.0f * std::tan(0.5f * fov_y_deg * 3.14159265f / 180.0f) / 480.0f;
        const float cos_theta = dot(to_p, normalize(target - eye)) / r;
        const float cos_incidence = std::fabs(to_p.y) / r;
        const float expected = std::sqrt(s * s * cos_theta * cos_theta * cos_theta * r * r / cos_incidence);
        CHECK(channel(aovs, Role::PixelSize)(x, y) == Approx(expected).epsilon(0.03));
    }
}

TEST_CASE("Render rejects bad settings and unknown scenes", "[trace]") {
    auto rejects = [](auto change) {
        trace::RenderSettings settings;
        change(settings);
        CHECK_THROWS_AS(trace::render_scene("grids", settings), Error);
    };
    rejects([](trace::RenderSettings &s) { s.width = 0; });
    rejects([](trace::RenderSettings &s) { s.height = 16385; });
    rejects([](trace::RenderSettings &s) { s.spp = 0; });
    rejects([](trace::RenderSettings &s) { s.spp = (1 << 20) + 1; });
    rejects([](trace::RenderSettings &s) { s.threads = -1; });
    CHECK_THROWS_WITH(trace::render_scene("nope", trace::RenderSettings{}), Catch::Contains("grids"));
    const auto names = trace::builtin_scene_names();
    CHECK(std::find(names.begin(), names.end(), "grids") != names.end());
}

TEST_CASE("Adaptive sampling follows the plan, capped, and is thread-count independent",
          "[trace][adaptive]") {
    trace::RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.adaptive = true;
    settings.max_spp = 60;
    settings.threads = 1;
    const AovSet one = trace::render_scene("grids", settings);
    settings.threads = 2;
    CHECK(same_channels(one, trace::render_scene("grids", settings)));

    int above_first_pass = 0;
    for (int y = 0; y < one.height(); ++y)
        for (int x = 0; x < one.width(); ++x) {
            if (channel(one, Role::ObjectId)(x, y) == 0) continue;
            const float spp = channel(one, Role::SamplesPerPixel)(x, y);
            REQUIRE(spp >= 9.0f);
            REQUIRE(spp <= 60.0f);
            if (spp > 9.0f) ++above_first_pass;
        }
    CHECK(above_first_pass > 100);
}

TEST_CASE("Cosine falloff keeps visibility in [0, 1] and exactly 1 when unoccluded", "[trace][falloff]") {
    trace::RenderSettings settings;
    settings.width = 48;
    settings.height = 36;
    settings.spp = 16;
    settings.cosine_falloff = true;
    const AovSet aovs = trace::render_scene("grids", settings);
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            const float v = channel(aovs, Role::Visibility)(x, y);
            REQUIRE(v >= 0.0f);
            REQUIRE(v <= 1.0f);
            if (channel(aovs, Role::D2Max)(x, y) == 0) CHECK(v == 1.0f);
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
    const AovSet aovs = trace::render_scene("grids", settings);
    int ground = 0;
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            if (channel(aovs, Role::ObjectId)(x, y) != 1.0f) continue;
            ++ground;
            const float d2_max = channel(aovs, Role::D2Max)(x, y);
            if (d2_max > 0)
                REQUIRE(d2_max <= channel(aovs, Role::D1)(x, y) - 0.33f);
            else
                REQUIRE(channel(aovs, Role::Visibility)(x, y) == 1.0f);
        }
    CHECK(ground > 1000);
}
