#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../scratch_dir.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/trace/render.h"
#include "random.h"
#include "ratio_sampling.h"
#include "renderer.h"
#include "scene_file.h"
#include "shading.h"
#include "surface_texture.h"

using namespace aaf;

namespace {

/// A textured, normal-mapped floor under two lights of different sizes and
/// colours; `occluders` adds a box and a sphere casting penumbrae, `glossy` a
/// GGX lobe on the floor.
std::string write_scene(const std::string &name, bool occluders, bool glossy) {
    const std::filesystem::path dir = aaf_test::scratch_dir("ratio_" + name);
    const std::filesystem::path path = dir / (name + ".json");
    std::ofstream out(path);
    out << R"({"format_version": 1, "name": ")" << name << R"(",
 "camera": {"type": "pinhole", "position": [0, 3, 3], "look_at": [0, 0, 0], "fov_y_deg": 50},
 "materials": {"floor": {"albedo": [0.7, 0.6, 0.5], "checker": {"size_m": 0.4, "albedo": [0.3, 0.4, 0.2]},
                         "bump": {"slope": 0.3, "period_m": 0.2})"
        << (glossy ? R"(, "specular": 0.04, "roughness": 0.4)" : "") << R"(},
               "grey": {"albedo": 0.5}},
 "lights": [{"center": [0, 2, 0], "edge_u": [1.2, 0, 0], "edge_v": [0, 0, 0.8], "intensity": 20,
             "color": [1, 0.8, 0.6], "profile": "uniform"},
            {"center": [1.5, 1.0, -0.5], "edge_u": [0, 0, 0.3], "edge_v": [-0.26, 0.15, 0], "intensity": 5,
             "color": [0.5, 0.7, 1], "profile": "uniform"}],
 "objects": [{"type": "plane", "size": [6, 6], "id": 1, "material": "floor"})"
        << (occluders ? R"(,
             {"type": "box", "min": [-0.3, 0.5, -0.3], "max": [0.3, 0.6, 0.3], "id": 2, "material": "grey"},
             {"type": "sphere", "center": [0.9, 0.35, 0.2], "radius": 0.25, "id": 3, "material": "grey"})"
                      : "")
        << "]}\n";
    return path.string();
}

trace::RenderSettings ratio_settings(int spp) {
    trace::RenderSettings settings;
    settings.width = 24;
    settings.height = 18;
    settings.spp = spp;
    settings.seed = 5;
    settings.threads = 2;
    settings.aovs = {"ratio"};
    return settings;
}

std::string layer(int light, const char *name) {
    return light < 0 ? std::string("ratio.") + name : "ratio.L" + std::to_string(light) + "." + name;
}

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

TEST_CASE("Ratio: U_N converges to the analytic U as N grows, per light, on a textured Lambertian floor",
          "[trace][ratio]") {
    const std::string scene = write_scene("open", false, false);
    for (int light = 0; light < 2; ++light) {
        INFO("light " << light);
        std::vector<double> errors;
        for (int spp : {1, 4, 16, 64, 256}) {
            const AovSet aovs = trace::render_scene(scene, ratio_settings(spp));
            const auto u = aovs.channel(layer(light, "U.R")), un = aovs.channel(layer(light, "Un.R"));
            double squared = 0, sum_u = 0;
            int count = 0;
            for (int y = 0; y < aovs.height(); ++y)
                for (int x = 0; x < aovs.width(); ++x)
                    if (u(x, y) > 0) {
                        squared += double(un(x, y) - u(x, y)) * double(un(x, y) - u(x, y));
                        sum_u += u(x, y);
                        ++count;
                    }
            REQUIRE(count > 100);
            errors.push_back(std::sqrt(squared / count) / (sum_u / count));
        }
        INFO("relative RMS errors at 1, 4, 16, 64, 256 spp: "
             << errors[0] << " " << errors[1] << " " << errors[2] << " " << errors[3] << " " << errors[4]);
        // Monte Carlo halves its error per quadrupling; allow some slack per step.
        for (std::size_t k = 1; k < errors.size(); ++k) CHECK(errors[k] < 0.7 * errors[k - 1]);
        CHECK(errors.back() < errors.front() / 8);
    }
}

TEST_CASE("Ratio: without occluders S_N equals U_N bit for bit, per light and summed", "[trace][ratio]") {
    const AovSet aovs = trace::render_scene(write_scene("open_glossy", false, true), ratio_settings(3));
    REQUIRE(std::get<int>(aovs.attributes.at(attr::kRatioLights)) == 2);
    for (int light = -1; light < 2; ++light)
        for (const char *c : {"R", "G", "B", "Y"}) {
            const auto s = aovs.channel(layer(light, (std::string("S.") + c).c_str()));
            const auto un = aovs.channel(layer(light, (std::string("Un.") + c).c_str()));
            for (int y = 0; y < aovs.height(); ++y)
                for (int x = 0; x < aovs.width(); ++x) REQUIRE(same_bits(s(x, y), un(x, y)));
        }
}

TEST_CASE("Ratio: S_N <= U_N, both >= 0, W in [0, 1], background zero, the estimators follow from the layers",
          "[trace][ratio]") {
    trace::RenderSettings settings = ratio_settings(2);
    settings.width = 48;
    settings.height = 36;
    settings.aovs = {"ratio", "ratio_estimators", "id"};
    const AovSet aovs = trace::render_scene("livingroom", settings);
    const int lights = std::get<int>(aovs.attributes.at(attr::kRatioLights));
    REQUIRE(lights == 3);
    int shadowed = 0, lit = 0;
    for (int light = -1; light < lights; ++light)
        for (const char *c : {"R", "G", "B", "Y"}) {
            const auto s = aovs.channel(layer(light, (std::string("S.") + c).c_str()));
            const auto un = aovs.channel(layer(light, (std::string("Un.") + c).c_str()));
            for (int y = 0; y < aovs.height(); ++y)
                for (int x = 0; x < aovs.width(); ++x) {
                    REQUIRE(s(x, y) >= 0);
                    REQUIRE(s(x, y) <= un(x, y));
                    if (un(x, y) > 0) {
                        const float w = s(x, y) / un(x, y);
                        REQUIRE(w >= 0);
                        REQUIRE(w <= 1);
                        (w < 1 ? shadowed : lit) += 1;
                    }
                }
        }
    CHECK(shadowed > 100);  // occluders cast shadows
    CHECK(lit > 100);       // and many pixels see every sample unoccluded
    const auto id = aovs.channel("id.object");
    for (const char *c : {"R", "G", "B"}) {
        const auto u = aovs.channel(layer(-1, (std::string("U.") + c).c_str()));
        const auto s = aovs.channel(layer(-1, (std::string("S.") + c).c_str()));
        const auto un = aovs.channel(layer(-1, (std::string("Un.") + c).c_str()));
        const auto sto = aovs.channel(std::string("ratio.sto.") + c);
        const auto cv = aovs.channel(std::string("ratio.cv.") + c);
        for (int y = 0; y < aovs.height(); ++y)
            for (int x = 0; x < aovs.width(); ++x) {
                REQUIRE(u(x, y) >= 0);
                if (id(x, y) == 0) REQUIRE((u(x, y) == 0 && s(x, y) == 0 && un(x, y) == 0));
                CHECK(sto(x, y) == Approx(s(x, y)).margin(1e-6));
                CHECK(cv(x, y) == Approx(u(x, y) - un(x, y) + s(x, y)).margin(1e-5));
            }
    }
}

TEST_CASE("Ratio: the layers are identical for any thread count", "[trace][ratio]") {
    trace::RenderSettings settings = ratio_settings(2);
    settings.threads = 1;
    const AovSet one = trace::render_scene("livingroom", settings);
    settings.threads = 2;
    const AovSet two = trace::render_scene("livingroom", settings);
    REQUIRE(one.channel_names() == two.channel_names());
    for (const std::string &name : one.channel_names()) {
        INFO(name);
        const auto a = one.channel(name), b = two.channel(name);
        for (int y = 0; y < one.height(); ++y)
            for (int x = 0; x < one.width(); ++x) REQUIRE(same_bits(a(x, y), b(x, y)));
    }
}

TEST_CASE("Ratio: E[S_N] (MIS of light and GGX samples) equals an independent area-sampled direct light",
          "[trace][ratio]") {
    // The same integrand, R L V over the light, estimated by uniform area
    // sampling on a fine grid: checks the MIS weights, the pdf conversions and
    // the spherical-rectangle map. S_N at 4 samples averaged over many seeds.
    trace::RenderSettings settings = ratio_settings(4);
    const std::string path = write_scene("occluded_glossy", true, true);
    const trace::SceneDescription scene = trace::load_scene_file(path, settings.width, settings.height);
    const trace::Renderer renderer(scene, settings);
    constexpr int kSeeds = 256, kMinHits = 16, kMaxSeeds = 1 << 16, kGrid = 128;
    int checked = 0;
    for (int y = 1; y < settings.height; y += 4)
        for (int x = 1; x < settings.width; x += 4) {
            const trace::PrimaryHit primary = renderer.trace_primary(x, y);
            if (!primary.found) continue;
            for (std::size_t light = 0; light < scene.lights.size(); ++light) {
                // Where the light is a sliver above the bumped horizon, few
                // samples reach it and the sample variance of a handful of
                // hits (or of none) misstates the spread: draw seeds until
                // kMinHits estimates are non-zero (or kMaxSeeds).
                double sum = 0, sum_sq = 0;
                int seeds = 0, hits = 0;
                for (; seeds < kSeeds || (hits < kMinHits && seeds < kMaxSeeds); ++seeds) {
                    const trace::RatioLayers layers = trace::trace_ratio_layers(
                        renderer.rays(), scene, primary, light, 4, std::uint64_t(seeds), 0);
                    sum += layers.shadowed.x;
                    sum_sq += double(layers.shadowed.x) * layers.shadowed.x;
                    if (layers.shadowed.x > 0) ++hits;
                }
                const double mean = sum / seeds;
                const double sigma_mean = std::sqrt(std::max(0.0, sum_sq / seeds - mean * mean) / seeds);

                const trace::SceneLight &emitter = scene.lights[light];
                const RectLight rect = trace::ratio_light(emitter);
                const trace::TexturedSurface surface =
                    trace::texture_surface(primary.mesh->material, primary.position, primary.normal);
                const Vec3 wo = normalize(scene.camera.eye - primary.position);
                double reference = 0;
                for (int j = 0; j < kGrid; ++j)
                    for (int i = 0; i < kGrid; ++i) {
                        const float u = ((i + 0.5f) / kGrid - 0.5f) * emitter.plane.width_m;
                        const float v = ((j + 0.5f) / kGrid - 0.5f) * emitter.plane.height_m;
                        const Vec3 point = emitter.plane.point_at(u, v);
                        const Vec3 to_light = point - primary.position;
                        const float distance_sq = dot(to_light, to_light);
                        const Vec3 wi = to_light / std::sqrt(distance_sq);
                        const float cos_light = -dot(emitter.plane.normal, wi);
                        const float cos_surface = dot(surface.normal, wi);
                        if (!(cos_light > 0) || !(cos_surface > 0)) continue;
                        if (renderer.light_point_blocked(primary, point)) continue;
                        const Vec3 f = trace::evaluate_brdf(surface.material, surface.normal, wo, wi);
                        reference += double(f.x) * rect.radiance.x * cos_surface * cos_light / distance_sq;
                    }
                reference *= double(emitter.plane.width_m) * emitter.plane.height_m / (double(kGrid) * kGrid);
                INFO("pixel " << x << "," << y << " light " << light << ", " << seeds << " seeds, " << hits
                              << " non-zero: E[S_N] " << mean << " +- " << sigma_mean << ", area-sampled "
                              << reference);
                // 4.5 standard errors, plus the grid's own error near shadow edges.
                CHECK(std::fabs(mean - reference) <= 4.5 * sigma_mean + 2e-3 * reference + 1e-7);
                ++checked;
            }
        }
    CHECK(checked > 20);
}

TEST_CASE("Ratio: --aovs all holds both ratio groups, and each is asked for by name", "[trace][ratio]") {
    CHECK(trace::parse_aov_groups("all").contains(trace::AovGroups{"ratio", "ratio_estimators"}));
    // "ratio" is also a method's name: it asks for every group the method reads (the ratio layer,
    // positions and normals), as `--aovs aaf` does for AAF.
    CHECK(trace::parse_aov_groups("ratio") == trace::aov_groups_for_method("ratio"));
    CHECK(trace::parse_aov_groups("ratio").contains("ratio"));
    CHECK(!trace::parse_aov_groups("ratio").contains("ratio_estimators"));
    CHECK(trace::parse_aov_groups("ratio_estimators") == trace::AovGroups{"ratio_estimators"});
}

TEST_CASE(
    "Ratio: with both techniques in use U_N converges per pixel at a fixed seed, also when N fills the grid",
    "[trace][ratio]") {
    // A glossy floor draws from the light and from the GGX lobe. At a perfect
    // square N the stratified grid is filled in sample order, so a technique
    // choice stratified over the sample index alone gave each technique a
    // fixed band of rows of the square (an azimuth band of the lobe): U_N was
    // unbiased over seeds but stopped converging as N grew. The reference is
    // the same integrand, R L over the light, on a fine area grid.
    trace::RenderSettings settings = ratio_settings(1);
    const std::string path = write_scene("open_glossy", false, true);
    const trace::SceneDescription scene = trace::load_scene_file(path, settings.width, settings.height);
    const trace::Renderer renderer(scene, settings);
    constexpr int kGrid = 256;
    const int spps[] = {16, 64, 256, 1024};
    for (std::size_t light = 0; light < scene.lights.size(); ++light) {
        double squared[4] = {0, 0, 0, 0}, sum_reference = 0;
        int count = 0;
        for (int y = 0; y < settings.height; y += 2)
            for (int x = 0; x < settings.width; x += 2) {
                const trace::PrimaryHit primary = renderer.trace_primary(x, y);
                if (!primary.found) continue;
                const trace::SceneLight &emitter = scene.lights[light];
                const RectLight rect = trace::ratio_light(emitter);
                const trace::TexturedSurface surface =
                    trace::texture_surface(primary.mesh->material, primary.position, primary.normal);
                const Vec3 wo = normalize(scene.camera.eye - primary.position);
                double reference = 0;
                for (int j = 0; j < kGrid; ++j)
                    for (int i = 0; i < kGrid; ++i) {
                        const float u = ((i + 0.5f) / kGrid - 0.5f) * emitter.plane.width_m;
                        const float v = ((j + 0.5f) / kGrid - 0.5f) * emitter.plane.height_m;
                        const Vec3 to_light = emitter.plane.point_at(u, v) - primary.position;
                        const float distance_sq = dot(to_light, to_light);
                        const Vec3 wi = to_light / std::sqrt(distance_sq);
                        const float cos_light = -dot(emitter.plane.normal, wi);
                        const float cos_surface = dot(surface.normal, wi);
                        if (!(cos_light > 0) || !(cos_surface > 0)) continue;
                        const Vec3 f = trace::evaluate_brdf(surface.material, surface.normal, wo, wi);
                        reference += double(f.x) * rect.radiance.x * cos_surface * cos_light / distance_sq;
                    }
                reference *= double(emitter.plane.width_m) * emitter.plane.height_m / (double(kGrid) * kGrid);
                if (!(reference > 0)) continue;
                for (int k = 0; k < 4; ++k) {
                    const trace::RatioLayers layers =
                        trace::trace_ratio_layers(renderer.rays(), scene, primary, light, spps[k],
                                                  settings.seed, std::uint64_t(y * 100 + x));
                    squared[k] += (layers.unshadowed.x - reference) * (layers.unshadowed.x - reference);
                }
                sum_reference += reference;
                ++count;
            }
        REQUIRE(count > 60);
        double errors[4];
        for (int k = 0; k < 4; ++k) errors[k] = std::sqrt(squared[k] / count) / (sum_reference / count);
        INFO("light " << light << ": relative RMS errors of U_N at 16, 64, 256, 1024 spp: " << errors[0]
                      << " " << errors[1] << " " << errors[2] << " " << errors[3]);
        // Monte Carlo at least halves its error per quadrupling (stratified,
        // faster); allow slack per step, not over the whole range.
        for (int k = 1; k < 4; ++k) CHECK(errors[k] < 0.8 * errors[k - 1]);
        CHECK(errors[3] < errors[0] / 8);
    }
}
