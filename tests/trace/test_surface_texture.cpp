#include <catch2/catch.hpp>

#include <cmath>

#include <filesystem>
#include <fstream>
#include <string>

#include "../scratch_dir.h"
#include "aaf/core/util/error.h"
#include "scene_file.h"
#include "surface_texture.h"

using namespace aaf;

namespace {

/// Loads a one-sphere scene whose material is `material` (JSON) and returns
/// the error message, or "" when it loads.
std::string material_error(const std::string &name, const std::string &material) {
    const std::filesystem::path path = aaf_test::scratch_dir("texture_" + name) / "scene.json";
    std::ofstream(path) << R"({"camera": {"position": [0, 2, 5], "look_at": [0, 0, 0]},
        "lights": [{"center": [0, 3, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1]}],
        "objects": [{"type": "sphere", "radius": 1, "material": )"
                        << material << "}]}";
    try {
        trace::load_scene_file(path.string(), 8, 8);
    } catch (const Error &e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("Textures: checker and bump are read, bad values are one line naming the file and field",
          "[trace][scene][errors][texture]") {
    using Catch::Contains;
    CHECK(material_error("ok", R"({"checker": {"size_m": 0.2, "albedo": [0.1, 0.2, 0.3]},
                                  "bump": {"slope": 0.4, "period_m": 0.05}})") == "");
    const std::pair<const char *, const char *> bad[] = {
        {R"({"checker": {"size_m": 0}})",
         "objects[0].material.checker.size_m: checker size_m must lie in [1e-4, 1e4]"},
        {R"({"checker": {"albedo": 0.5}})", "objects[0].material.checker: missing required field 'size_m'"},
        {R"({"checker": {"size_m": 1, "albedo": 1.5}})",
         "objects[0].material.checker: checker albedo must lie in [0, 1]"},
        {R"({"checker": {"size_m": 1, "colour": 0.5}})", "objects[0].material.checker.colour: unknown field"},
        {R"({"bump": {"slope": -1}})", "objects[0].material.bump: bump slope must lie in [0, 10]"},
        {R"({"bump": {"slope": 1, "period_m": 0}})",
         "objects[0].material.bump: bump period_m must lie in [1e-4, 1e4]"},
        {R"({"bump": {"period_m": 1}})", "objects[0].material.bump: missing required field 'slope'"},
    };
    for (const auto &[material, message] : bad) {
        const std::string error = material_error("bad", material);
        INFO(material);
        CHECK_THAT(error, Contains("scene.json: ") && Contains(message));
        CHECK(error.find('\n') == std::string::npos);
    }
}

TEST_CASE("Textures: an untextured material is unchanged, the checker alternates, the bump tilts the normal",
          "[trace][texture]") {
    trace::Material plain;
    plain.albedo = {0.3f, 0.5f, 0.7f};
    const Vec3 n{0, 1, 0};
    const trace::TexturedSurface same = trace::texture_surface(plain, {0.37f, 0.0f, -1.2f}, n);
    CHECK(same.material.albedo == plain.albedo);
    CHECK(same.normal == n);

    trace::Material checker = plain;
    checker.checker_size_m = 0.5f;
    checker.checker_albedo = {0.9f, 0.1f, 0.1f};
    // Neighbouring cells along x differ; cells two apart agree.
    const Vec3 a = trace::texture_surface(checker, {0.25f, 0.0f, 0.25f}, n).material.albedo;
    const Vec3 b = trace::texture_surface(checker, {0.75f, 0.0f, 0.25f}, n).material.albedo;
    const Vec3 c = trace::texture_surface(checker, {1.25f, 0.0f, 0.25f}, n).material.albedo;
    CHECK(a != b);
    CHECK(a == c);
    CHECK((a == plain.albedo || a == checker.checker_albedo));

    trace::Material bumped = plain;
    bumped.bump_slope = 0.5f;
    bumped.bump_period_m = 1.0f;
    // At x = 0 the height's x-slope is the full 0.5 (cos 0 = 1): the normal
    // tilts by atan(0.5) towards -x, stays a unit vector on n's side.
    const trace::TexturedSurface tilted = trace::texture_surface(bumped, {0.0f, 0.0f, 0.25f}, n);
    CHECK(length(tilted.normal) == Approx(1.0f));
    CHECK(tilted.normal.x == Approx(-0.5f / std::sqrt(1.25f)).margin(1e-5));
    CHECK(tilted.normal.y > 0);
}
