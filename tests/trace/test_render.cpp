#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/util/error.h"
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
std::vector<float> plane(const AovSet &aovs, const std::string &name) {
    const auto &names = aovs.channel_names();
    const AovSet::Plane &values =
        aovs.plane(std::size_t(std::find(names.begin(), names.end(), name) - names.begin()));
    return std::vector<float>(values.begin(), values.end());
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

TEST_CASE("Render runs as many threads as asked, even beyond the cores", "[trace][threads]") {
    // More threads than cores, so the thread-count tests mean something on any machine.
    const int threads = tbb::info::default_concurrency() + 2;
    trace::RenderSettings settings;
    settings.width = 8;
    settings.height = 6;
    settings.spp = 2;
    settings.threads = threads;
    int arena_threads = 0;
    std::size_t allowed = 0;
    settings.on_progress = [&](int, int) {  // called inside the render's arena
        arena_threads = tbb::this_task_arena::max_concurrency();
        allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    };
    trace::render_scene("grids", settings);
    CHECK(arena_threads == threads);
    CHECK(allowed >= std::size_t(threads));
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

namespace {

/// A 32x24 render of grids at 2 spp with the groups `aovs` (as `--aovs` reads it).
AovSet render_aovs(const std::string &aovs) {
    trace::RenderSettings settings;
    settings.width = 32;
    settings.height = 24;
    settings.spp = 2;
    settings.aovs = trace::parse_aov_groups(aovs);
    return trace::render_scene("grids", settings);
}

/// Whether `method`, at its defaults, has a plan ready to run on `aovs`.
bool plan_ready(const Method &method, const AovSet &aovs) {
    return prepare_filter(method, method.default_parameters(), aovs, ChannelMap{}).ready();
}

}  // namespace

TEST_CASE("A render with --aovs METHOD holds every input of the method: its plan is ready", "[trace]") {
    for (const Method *method : methods()) {
        INFO(method->info().name);
        const AovSet aovs = render_aovs(method->info().name);
        CHECK(missing_inputs(*method, aovs, ChannelMap{}).empty());
        CHECK(plan_ready(*method, aovs));
    }
}

TEST_CASE("A render with --aovs all leaves every registered method's plan ready", "[trace]") {
    const AovSet aovs = render_aovs("all");
    for (const Method *method : methods()) {
        INFO(method->info().name);
        CHECK(plan_ready(*method, aovs));
    }
}

TEST_CASE("A render with --aovs GROUP leaves ready every method that reads the group's own roles",
          "[trace]") {
    std::vector<Role> shared;
    for (const RoleInfo &info : shared_roles()) shared.push_back(info.role);
    for (const trace::AovGroupInfo &group : trace::aov_group_table()) {
        std::vector<const Method *> readers;
        for (const Method *method : methods()) {
            const std::vector<Role> &required = method->info().roles.required;
            for (Role role : group.roles)
                if (std::find(shared.begin(), shared.end(), role) == shared.end() &&
                    std::find(required.begin(), required.end(), role) != required.end()) {
                    readers.push_back(method);
                    break;
                }
        }
        if (readers.empty()) continue;
        const AovSet aovs = render_aovs(group.name);
        for (const Method *method : readers) {
            INFO("--aovs " << group.name << ", " << method->info().name);
            CHECK(plan_ready(*method, aovs));
        }
    }
}

TEST_CASE("Render writes every AAF AOV with consistent values", "[trace]") {
    const AovSet aovs = render_small(16, 1, 0);
    const ChannelMap map;
    // Every method whose groups the default render writes (maaf and isg read their own: `--aovs maaf`).
    for (const Method *method : methods())
        if (trace::RenderSettings{}.aovs.contains(trace::aov_groups_for_method(method->info().name)))
            CHECK(missing_inputs(*method, aovs, map).empty());
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

namespace {

/// Frame `frame` of a sequence of the static scene grids, 24x18 at 4 spp.
AovSet render_frame(double frame, bool seed_per_frame) {
    trace::RenderSettings settings;
    settings.width = 24;
    settings.height = 18;
    settings.spp = 4;
    settings.seed = 5;
    settings.frame = frame;
    settings.seed_per_frame = seed_per_frame;
    return trace::render_scene("grids", settings);
}

}  // namespace

TEST_CASE("Per-frame seeds give a static scene's frames their own noise, and the header records both seeds",
          "[trace][seed]") {
    const AovSet one = render_frame(1, true), two = render_frame(2, true);
    const std::vector<float> v1 = plane(one, role_info(Role::Visibility).channels[0]),
                             v2 = plane(two, role_info(Role::Visibility).channels[0]);
    std::size_t different = 0;
    for (std::size_t i = 0; i < v1.size(); ++i) different += v1[i] != v2[i];
    CHECK(different > 20);
    // Only the noise: the geometry is the same.
    CHECK(plane(one, role_info(Role::Position).channels[0]) ==
          plane(two, role_info(Role::Position).channels[0]));
    for (const auto &[aovs, frame] : {std::pair<const AovSet &, double>{one, 1}, {two, 2}}) {
        CHECK(aovs.attributes.at(attr::kSeed) == AttributeValue(int(trace::frame_seed(5, frame))));
        CHECK(aovs.attributes.at(attr::kBaseSeed) == AttributeValue(5));
    }
    CHECK(trace::frame_seed(5, 1) != trace::frame_seed(5, 2));
    CHECK(trace::frame_seed(5, 1) != trace::frame_seed(6, 1));
    CHECK(trace::frame_seed(5, 2) == trace::frame_seed(5, 2));
    CHECK(trace::frame_seed(~std::uint64_t(0), 7) <= 0x7fffffffu);  // aaf:seed is an int
}

TEST_CASE("A fixed seed gives a static scene's frames the same noise and records only the seed",
          "[trace][seed]") {
    const AovSet one = render_frame(1, false), two = render_frame(2, false);
    CHECK(same_channels(one, two));
    CHECK(one.attributes.at(attr::kSeed) == AttributeValue(5));
    CHECK(one.attributes.count(attr::kBaseSeed) == 0);
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
    rejects([](trace::RenderSettings &s) { s.threads = 1025; });  // not a million threads by a typo
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

namespace {

/// A scene that can be checked by hand: a thin square occluder 1 m above a
/// ground plane, lit by a uniform 0.5 m square light 3 m up, seen straight
/// down by a camera above the receiver point (0.9, 0, 0).
std::string write_probe_scene(const std::string &extra_lights = "") {
    const std::filesystem::path dir = std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / "probe_scene";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / (extra_lights.empty() ? "probe.json" : "probe_two_lights.json")).string();
    // Parallel test processes write this scene too: a temporary renamed into
    // place keeps any reader from seeing a half-written file.
    const std::string temporary = path + ".tmp-" + std::to_string(std::random_device{}());
    std::ofstream(temporary) << R"({
  "camera": {"position": [0.9, 2.5, 0], "look_at": [0.9, 0, 0], "up": [0, 0, -1], "fov_y_deg": 45},
  "lights": [{"center": [0, 3, 0], "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5], "intensity": 10,
              "profile": "uniform"})" +
                                    extra_lights + R"(],
  "objects": [
    {"type": "plane", "size": [10, 10], "id": 1, "material": {"albedo": 0.5}},
    {"type": "box", "min": [0.6, 1.0, -0.1], "max": [0.7, 1.01, 0.1], "id": 2}
  ]
})";
    std::filesystem::rename(temporary, path);
    return path;
}

}  // namespace

TEST_CASE("AOVs of a hand-checkable scene match its geometry", "[trace][geometry]") {
    trace::RenderSettings settings;
    settings.width = settings.height = 33;  // odd: the centre pixel's ray is the view axis
    settings.spp = 1024;
    // Every group that traces nothing of its own (at 1024 spp the others would be slow).
    settings.aovs = {"shadow", "position", "normal", "id",      "unshadowed",
                     "depth",  "albedo",   "motion", "progress"};
    const AovSet aovs = trace::render_scene(write_probe_scene(), settings);
    const int c = 16;
    const Vec3 p = position(aovs, c, c);
    CHECK(p.x == Approx(0.9f).margin(1e-5));
    CHECK(p.y == Approx(0.0f).margin(1e-5));
    CHECK(p.z == Approx(0.0f).margin(1e-5));
    CHECK(channel(aovs, Role::Normal, 1)(c, c) == 1.0f);
    CHECK(channel(aovs, Role::ObjectId)(c, c) == 1.0f);
    CHECK(channel(aovs, Role::Depth)(c, c) == Approx(2.5f));
    // d1: the receiver lies 3 m below the light's plane.
    CHECK(channel(aovs, Role::D1)(c, c) == Approx(3.0f));
    // Rays towards the light enter the occluder through its bottom (1 m up,
    // 2 m below the light) or, near its edge, its side between 1 and 1.01 m.
    CHECK(channel(aovs, Role::D2Max)(c, c) == Approx(2.0f).margin(1e-4));
    CHECK(channel(aovs, Role::D2Min)(c, c) >= 1.99f - 1e-4f);
    CHECK(channel(aovs, Role::D2Min)(c, c) <= 2.0f + 1e-4f);
    // Seen from the receiver, the occluder (x in [0.6, 0.7] at 1 m) covers the
    // light's plane for x in [0, 0.3], i.e. exactly half of the light.
    CHECK(channel(aovs, Role::Visibility)(c, c) == Approx(0.5f).margin(0.01));
    // Straight down from 2.5 m, a pixel spans 2.5 * 2 tan(22.5 deg) / 33 metres.
    CHECK(channel(aovs, Role::PixelSize)(c, c) ==
          Approx(2.5 * 2 * std::tan(22.5 * 3.14159265358979 / 180) / 33).epsilon(1e-4));
    // r(x) = albedo / pi * I * cos * cos / r^2 towards the centre (0, 3, 0): r^2 = 9.81.
    const double unshadowed = 0.5 / 3.14159265358979 * 10 * (9 / 9.81) / 9.81;
    CHECK(channel(aovs, Role::Unshadowed, 0)(c, c) == Approx(unshadowed).epsilon(1e-4));
    CHECK(channel(aovs, Role::Beauty, 1)(c, c) ==
          Approx(unshadowed * channel(aovs, Role::Visibility)(c, c)).epsilon(1e-5));
    CHECK(channel(aovs, Role::Albedo, 2)(c, c) == 0.5f);
    CHECK(channel(aovs, Role::Motion, 0)(c, c) == 0.0f);  // a still camera
}

TEST_CASE("No light leaks through a thin slab onto the ground below it", "[trace][geometry]") {
    // A 1 cm slab 1 m up, 4 m wide, hides the 0.5 m light (3 m up) from every
    // ground point within 1 m of the centre; seen from below the slab, each
    // of those points must be exactly dark, whatever the sample.
    const std::filesystem::path dir = std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / "probe_scene";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "slab.json").string();
    std::ofstream(path) << R"({
  "camera": {"position": [0, 0.5, 3.0], "look_at": [0, 0, 0], "fov_y_deg": 30},
  "lights": [{"center": [0, 3, 0], "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5], "intensity": 10}],
  "objects": [
    {"type": "plane", "size": [10, 10], "id": 1, "material": {"albedo": 0.5}},
    {"type": "box", "min": [-2, 1.0, -2], "max": [2, 1.01, 2], "id": 2}
  ]
})";
    trace::RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.spp = 64;
    const AovSet aovs = trace::render_scene(path, settings);
    int checked = 0;
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            const Vec3 p = position(aovs, x, y);
            if (channel(aovs, Role::ObjectId)(x, y) != 1 || std::abs(p.x) > 1 || std::abs(p.z) > 1) continue;
            ++checked;
            CHECK(channel(aovs, Role::Visibility)(x, y) == 0.0f);
            CHECK(channel(aovs, Role::Beauty, 0)(x, y) == 0.0f);
        }
    CHECK(checked > 500);
}

TEST_CASE("A second light adds its shadowed shading to the beauty, not to the AAF AOVs", "[trace][lights]") {
    trace::RenderSettings settings;
    settings.width = settings.height = 17;
    settings.spp = 16;
    const AovSet one = trace::render_scene(write_probe_scene(), settings);
    const AovSet two = trace::render_scene(
        write_probe_scene(
            R"(, {"center": [3, 3, 0], "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5], "intensity": 5})"),
        settings);
    CHECK(plane(one, "shadow.V") == plane(two, "shadow.V"));
    CHECK(plane(one, "unshadowed.R") == plane(two, "unshadowed.R"));
    REQUIRE(two.has_channel("otherlights.R"));
    CHECK_FALSE(one.has_channel("otherlights.R"));
    bool lit_by_second = false;
    for (int y = 0; y < 17; ++y)
        for (int x = 0; x < 17; ++x) {
            const float other = two.channel("otherlights.G")(x, y);
            lit_by_second |= other > 0;
            CHECK(two.channel("G")(x, y) == Approx(one.channel("G")(x, y) + other).epsilon(1e-5));
        }
    CHECK(lit_by_second);

    // AAF filters the key light's shadow and adds the other lights back.
    const AovSet filtered = aaf_filter_aovs(two, ChannelMap{}, AafParams{});
    for (int y = 0; y < 17; ++y)
        for (int x = 0; x < 17; ++x)
            CHECK(filtered.channel("G")(x, y) ==
                  Approx(two.channel("unshadowed.G")(x, y) * filtered.channel("aaf.V")(x, y) +
                         two.channel("otherlights.G")(x, y))
                      .epsilon(1e-6));
}

TEST_CASE("A thin lens with a vanishing aperture gives the pinhole's beauty", "[trace][lens]") {
    const std::filesystem::path dir = std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / "lens_scene";
    std::filesystem::create_directories(dir);
    auto write_scene = [&](const std::string &name, const std::string &lens) {
        const std::string path = (dir / name).string();
        std::ofstream(path) << R"({"camera": {"position": [0, 4.2, 5.2], "look_at": [0, 0.2, 0])" << lens
                            << R"(},
  "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "intensity": 30}],
  "objects": [{"type": "plane", "size": [20, 20]}, {"type": "sphere", "center": [0, 0.8, 0], "radius": 0.5, "id": 2}]})";
        return path;
    };
    trace::RenderSettings settings;
    settings.width = 40;
    settings.height = 30;
    settings.spp = 64;
    const AovSet pinhole = trace::render_scene(write_scene("pinhole.json", ""), settings);
    const AovSet lens = trace::render_scene(
        write_scene("lens.json", R"(, "type": "thin_lens", "aperture_radius_m": 1e-6)"), settings);
    // Same light samples, same hit points (up to the 1 um aperture): the same shading.
    int close = 0;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x)
            close += std::fabs(lens.channel("R")(x, y) - pinhole.channel("R")(x, y)) < 1e-3f;
    CHECK(close >= 40 * 30 - 12);  // a few silhouette pixels may flip

    // A wide aperture focused far behind the sphere blurs it: the image moves
    // away from the pinhole's by far more than the noise of another seed does.
    const AovSet blurred = trace::render_scene(
        write_scene("wide.json",
                    R"(, "type": "thin_lens", "aperture_radius_m": 0.3, "focus_distance_m": 12)"),
        settings);
    settings.seed = 2;
    const AovSet reseeded = trace::render_scene(write_scene("pinhole.json", ""), settings);
    double blur_difference = 0, noise_difference = 0;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            blur_difference += std::fabs(blurred.channel("R")(x, y) - pinhole.channel("R")(x, y));
            noise_difference += std::fabs(reseeded.channel("R")(x, y) - pinhole.channel("R")(x, y));
        }
    CHECK(blur_difference > 2 * noise_difference);
}

TEST_CASE("Motion vectors of a sideways camera move match the pinhole projection", "[trace][motion]") {
    const std::filesystem::path dir = std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / "motion_scene";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "motion.json").string();
    // Straight down from 2.5 m; between frames 1 and 2 the camera slides 0.1 m along +x (raster +x).
    std::ofstream(path) << R"({
  "camera": {"position": [0.9, 2.5, 0], "look_at": [0.9, 0, 0], "up": [0, 0, -1], "fov_y_deg": 45},
  "lights": [{"center": [0, 3, 0], "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5]}],
  "objects": [{"type": "plane", "size": [10, 10]}],
  "animation": {"camera": [{"frame": 1}, {"frame": 2, "position": [1.0, 2.5, 0], "look_at": [1.0, 0, 0]}]}
})";
    trace::RenderSettings settings;
    settings.width = settings.height = 33;
    settings.spp = 1;
    settings.aovs = {"motion", "position"};
    settings.frame = 2;
    const AovSet aovs = trace::render_scene(path, settings);
    // The point under the centre, (1.0, 0, 0), sat 0.1 m right of the old
    // camera's axis at 2.5 m depth: 0.1 / (2.5 * 2 tan(22.5 deg) / 33) pixels.
    const double pixel_m = 2.5 * 2 * std::tan(22.5 * 3.14159265358979 / 180) / 33;
    CHECK(position(aovs, 16, 16).x == Approx(1.0f));
    CHECK(aovs.channel("motion.X")(16, 16) == Approx(-0.1 / pixel_m).epsilon(1e-3));
    CHECK(aovs.channel("motion.Y")(16, 16) == Approx(0.0).margin(1e-4));
    settings.frame = 1;  // before the first key the camera holds still
    CHECK(trace::render_scene(path, settings).channel("motion.X")(16, 16) == 0.0f);
}

TEST_CASE("An object's keyframes move it, and its motion vectors follow it", "[trace][motion]") {
    const std::filesystem::path dir =
        std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / "moving_object";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "moving.json").string();
    // Straight down from 2.5 m on a still camera; a thin 1 m square slab
    // 0.5 m above the floor slides 0.1 m along +x (raster +x) from frame 1 to 2.
    std::ofstream(path) << R"({
  "camera": {"position": [0, 2.5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov_y_deg": 45},
  "lights": [{"center": [0, 3, 0], "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5]}],
  "objects": [{"type": "plane", "size": [10, 10]},
              {"type": "box", "min": [-0.5, 0.5, -0.5], "max": [0.5, 0.52, 0.5]}],
  "animation": {"objects": [{"object": 1, "keys": [{"frame": 1, "offset": [0, 0, 0]},
                                                   {"frame": 2, "offset": [0.1, 0, 0]}]}]}
})";
    trace::RenderSettings settings;
    settings.width = settings.height = 33;
    settings.spp = 1;
    settings.aovs = {"motion", "position", "id"};
    settings.frame = 2;
    const AovSet aovs = trace::render_scene(path, settings);
    // The slab's top, 1.98 m from the camera, moved 0.1 m: 0.1 / (1.98 * 2 tan(22.5 deg) / 33) pixels.
    const double pixel_m = 1.98 * 2 * std::tan(22.5 * 3.14159265358979 / 180) / 33;
    CHECK(aovs.channel("id.object")(16, 16) == 2.0f);
    CHECK(position(aovs, 16, 16).y == Approx(0.52f));
    CHECK(aovs.channel("motion.X")(16, 16) == Approx(0.1 / pixel_m).epsilon(1e-3));
    CHECK(aovs.channel("motion.Y")(16, 16) == Approx(0.0).margin(1e-4));
    // The floor beside it stays still; the slab's left edge (x = -0.5 m at
    // frame 1, -0.4 m at frame 2) uncovered the floor under pixel 7 (-0.45 m).
    CHECK(aovs.channel("id.object")(1, 16) == 1.0f);
    CHECK(aovs.channel("motion.X")(1, 16) == 0.0f);
    CHECK(aovs.channel("id.object")(7, 16) == 1.0f);
    settings.frame = 1;  // before the first key the slab holds still
    const AovSet first = trace::render_scene(path, settings);
    CHECK(first.channel("id.object")(7, 16) == 2.0f);
    CHECK(first.channel("motion.X")(16, 16) == 0.0f);
}

TEST_CASE("A receiver on the light's centre gets finite shading", "[trace][lights][limits]") {
    // The camera looks straight down the y axis at the ground, so the centre
    // pixel of an odd-sized image hits the origin: the light's centre, where
    // the receiver-light direction of r(x) (AAF Eq. 1) is 0 / 0.
    const std::filesystem::path dir =
        std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / "light_on_receiver";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "scene.json").string();
    std::ofstream(path) << R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1]},
  "lights": [{"center": [0, 0, 0], "edge_u": [0, 0, 1], "edge_v": [1, 0, 0], "intensity": 30}],
  "objects": [{"type": "plane", "size": [20, 20]}]})";
    trace::RenderSettings settings;
    settings.width = 9;
    settings.height = 9;
    settings.spp = 4;
    settings.aovs = {"shadow", "unshadowed", "position"};
    const AovSet aovs = trace::render_scene(path, settings);
    REQUIRE(aovs.channel("P.X")(4, 4) == 0.0f);  // the pixel that hits the centre exactly
    REQUIRE(aovs.channel("P.Z")(4, 4) == 0.0f);
    for (const char *name : {"R", "G", "B", "unshadowed.R"})
        for (int y = 0; y < 9; ++y)
            for (int x = 0; x < 9; ++x) {
                INFO(name << " at " << x << ", " << y);
                CHECK(std::isfinite(aovs.channel(name)(x, y)));
            }
}
