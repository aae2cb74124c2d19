#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "../golden_hash.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/trace/render.h"

// Golden hashes of small renders, taken before the AOV groups became
// accumulators: every channel's name, precision and float bits and every
// header attribute must stay byte-identical through refactors of how the
// AOVs are written. A failing check prints the new hash; update one only
// when a render is meant to change.
//
// The bytes are pinned to sse4.2, which every x86-64 CPU has: Embree only
// finds the triangle and the tracer computes where the ray meets it
// (EmbreeScene::intersect), so under that pin the hash holds on any x86-64
// CPU for this build (GCC or Clang, Release, Embree 3). Under the wider sets
// this CPU runs (avx2, avx512) Embree's kernels may pick the neighbouring
// triangle for a ray through a shared edge, so there the render must match
// the pinned one's header and all but at most 0.1% of its values
// (aaf_test::kEdgeGrazingFraction, the bound of test_instruction_sets.cpp).

using namespace aaf;
using aaf_test::golden_hash;
using aaf_test::hex;
using aaf_test::instruction_sets_here;

namespace {

/// Checks the hash of `render()` pinned to sse4.2, and that every wider set
/// this CPU runs gives the same bytes or differs in at most 0.1% of the
/// values; the process's own setting is restored afterwards.
template <typename Render>
void check_golden(const Render &render, std::uint64_t expected) {
    const InstructionSet before = instruction_set();
    set_instruction_set(InstructionSet::Sse42);
    const AovSet pinned = render();
    const std::uint64_t hash = golden_hash(pinned);
    INFO("pinned to sse4.2: hash " << hex(hash) << ", golden " << hex(expected));
    CHECK(hash == expected);
    for (InstructionSet set : instruction_sets_here()) {
        if (set == InstructionSet::Sse42) continue;
        set_instruction_set(set);
        const AovSet wider = render();
        const aaf_test::Agreement a = aaf_test::agreement(pinned, wider, 0.0);
        INFO(instruction_set_name(set)
             << " against sse4.2: fraction of values that differ " << a.fraction_beyond);
        CHECK(wider.attributes == pinned.attributes);
        CHECK(a.fraction_beyond <= aaf_test::kEdgeGrazingFraction);
    }
    set_instruction_set(before);
}

/// The groups the goldens were taken with: every group that traces no rays
/// of its own and keeps the light samples' stratification (what `--aovs all`
/// wrote then).
trace::AovGroups golden_groups() {
    return {"shadow", "position", "normal", "id", "unshadowed", "depth", "albedo", "motion", "progress"};
}

trace::RenderSettings small_settings() {
    trace::RenderSettings settings;
    settings.width = 32;
    settings.height = 24;
    settings.spp = 4;
    settings.seed = 7;
    settings.threads = 2;
    settings.aovs = golden_groups();
    return settings;
}

/// A pinhole scene with two lights of different profiles: the other lights'
/// shading (otherlights.*) and the progress radiance sums are not zero.
std::string write_two_light_scene() {
    const std::filesystem::path dir = std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / "golden";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "two_lights.json").string();
    // ctest runs this file's cases as parallel processes that all write this
    // scene: each writes its own temporary and renames it into place, so no
    // reader ever sees a half-written file.
    const std::string temporary = path + ".tmp-" + std::to_string(std::random_device{}());
    std::ofstream(temporary) << R"({
  "camera": {"position": [0.5, 2.5, 1.5], "look_at": [0.5, 0, 0], "up": [0, 1, 0], "fov_y_deg": 50},
  "lights": [{"center": [0, 3, 0], "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5], "intensity": 10},
             {"center": [2, 2.5, 1], "edge_u": [0.3, 0, 0], "edge_v": [0, 0, 0.3], "intensity": 4,
              "profile": "uniform"}],
  "objects": [
    {"type": "plane", "size": [10, 10], "id": 1, "material": {"albedo": 0.5}},
    {"type": "box", "min": [0.3, 0.6, -0.2], "max": [0.7, 0.7, 0.2], "id": 2}
  ]
})";
    std::filesystem::rename(temporary, path);
    return path;
}

}  // namespace

TEST_CASE("Every shipped scene renders its AOVs to the golden bytes", "[trace][golden]") {
    const std::pair<const char *, std::uint64_t> golden[] = {
        {"bench", 0x5c79f14cfd2abf9a},
        {"contact", 0x4ea9306636419d43},
        {"gallery", 0x3fcbd40f8f3c712a},  // ISG's scene
        {"grazing", 0xb190c52cb49ae1e7},
        {"grids", 0x822ff7796dc0575a},
        {"livingroom", 0x2d9d9e0504c297c3},  // the ratio estimator's scene: textures, normal maps, three
                                             // lights
        {"room", 0x524aef9bd65c6b87},        // MAAF's combined effects (thin lens of 0.15 m, coloured walls)
        {"spheres", 0x43687136f19d2416},
        {"studio", 0xd7176942a8ed43b1},  // thin lens, two lights, animated camera
        {"tentacles", 0xb63f6ce73e4d96ff},
        {"tilted", 0x7670b02529bcadc9},
    };
    REQUIRE(trace::builtin_scene_names().size() == std::size(golden));
    for (std::size_t i = 0; i < std::size(golden); ++i) {
        INFO("scene " << golden[i].first);
        REQUIRE(trace::builtin_scene_names()[i] == golden[i].first);
        check_golden([&] { return trace::render_scene(golden[i].first, small_settings()); },
                     golden[i].second);
    }
}

// Skipping self-occluded light samples (no occluder distance, the AAF
// authors' convention; RenderSettings::skip_self_occluded) changes the
// occluder distances of every scene with surfaces turned from the light.
TEST_CASE("Skipping self-occluded samples gives its own golden bytes", "[trace][golden]") {
    const std::pair<const char *, std::uint64_t> golden[] = {
        {"bench", 0x490206e7f532effa},  {"grids", 0xc2874cec91b94d42},     {"spheres", 0xf6eb5e669312f1b1},
        {"studio", 0x2245afe8c6ecc312}, {"tentacles", 0x81e9f274a7b48005},
    };
    trace::RenderSettings settings = small_settings();
    settings.skip_self_occluded = true;
    for (const auto &scene : golden) {
        INFO("scene " << scene.first);
        check_golden([&] { return trace::render_scene(scene.first, settings); }, scene.second);
    }
}

TEST_CASE("An adaptive render gives the golden bytes", "[trace][golden]") {
    trace::RenderSettings settings = small_settings();
    settings.spp = 9;
    settings.adaptive = true;
    settings.max_spp = 40;
    // Changed on purpose four times: when the second pass began tracing
    // visibility only (occluder distances from the first pass, AAF Sec. 6:
    // only shadow.d2min/d2max differed), when the plan began measuring the
    // pixel footprint in the light plane's units, and when the plan's
    // defaults went back to the paper's band-limit 1/sigma and the receiver's
    // footprint (libaaf/core/methods/aaf/README.md: fewer samples), and
    // when hits began to be computed by the tracer (the same on every CPU).
    check_golden([&] { return trace::render_scene("grids", settings); }, 0x554eac6c160fa23d);
    // The former defaults still give their bytes: the truncated profile's
    // equivalent-width band-limit with the projected footprint, then with the receiver's.
    settings.plan.light_bandlimit = LightBandlimit::EquivalentWidth;
    settings.plan.projected_pixel = true;
    check_golden([&] { return trace::render_scene("grids", settings); }, 0x8bc8cabe6f6e3140);
    settings.plan.projected_pixel = false;
    check_golden([&] { return trace::render_scene("grids", settings); }, 0xe5a5e1624d848929);
}

TEST_CASE("Two lights, a uniform profile and the cosine falloff give the golden bytes", "[trace][golden]") {
    trace::RenderSettings settings = small_settings();
    settings.cosine_falloff = true;
    check_golden([&] { return trace::render_scene(write_two_light_scene(), settings); }, 0xc9fa2ea681efac9d);
    settings.cosine_falloff = false;
    settings.light_profile = LightProfile::Uniform;
    check_golden([&] { return trace::render_scene(write_two_light_scene(), settings); }, 0x9237fc0136942b79);
}

TEST_CASE("A stopped reference and its resumption give the golden bytes", "[trace][golden]") {
    trace::RenderSettings settings = small_settings();
    settings.width = 16;
    settings.height = 12;
    settings.spp = 2 * trace::kSamplesPerRound + 8;
    settings.aovs = trace::aov_groups_for_method("aaf");  // progress is added for a reference
    settings.stop_requested = [] { return true; };
    const AovSet partial = trace::render_scene(write_two_light_scene(), settings);
    REQUIRE(std::get<int>(partial.attributes.at(attr::kSppDone)) == trace::kSamplesPerRound);
    check_golden([&] { return trace::render_scene(write_two_light_scene(), settings); }, 0x14318847f0b625c9);
    settings.stop_requested = nullptr;
    settings.resume = &partial;
    check_golden([&] { return trace::render_scene(write_two_light_scene(), settings); }, 0x8d07a971c8353f8b);
}

TEST_CASE("The isg group renders the gallery to the golden bytes", "[trace][golden]") {
    trace::RenderSettings settings = small_settings();
    settings.aovs = golden_groups() | trace::AovGroups{"isg"};
    check_golden([&] { return trace::render_scene("gallery", settings); }, 0xd91491eb0b232e5f);
}
