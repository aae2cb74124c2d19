// Resuming renders: a reference continued after its first round, a
// checkpoint between rounds, a partial render that ends inside a round, and
// an edited scene refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/util/error.h"
#include "aaf/trace/render.h"

using namespace aaf;

namespace {

/// The stored plane of the channel called `name`.
std::vector<float> plane(const AovSet &aovs, const std::string &name) {
    const auto &names = aovs.channel_names();
    const AovSet::Plane &values =
        aovs.plane(std::size_t(std::find(names.begin(), names.end(), name) - names.begin()));
    return std::vector<float>(values.begin(), values.end());
}

}  // namespace

TEST_CASE("A reference resumed after its first round equals one rendered in one go", "[trace][resume]") {
    trace::RenderSettings settings;
    settings.width = 24;
    settings.height = 18;
    settings.spp = 2 * trace::kSamplesPerRound;
    const AovSet whole = trace::render_scene("grids", settings);
    settings.spp = trace::kSamplesPerRound;
    const AovSet half = trace::render_scene("grids", settings);
    settings.spp = 2 * trace::kSamplesPerRound;
    settings.resume = &half;
    const AovSet resumed = trace::render_scene("grids", settings);
    REQUIRE(resumed.channel_names() == whole.channel_names());
    for (std::size_t i = 0; i < whole.channel_names().size(); ++i) {
        INFO(whole.channel_names()[i]);
        CHECK(resumed.plane(i) == whole.plane(i));
    }
    CHECK(std::get<int>(resumed.attributes.at(attr::kSppDone)) == settings.spp);

    // Resuming a finished render (even one that ends inside a round) adds nothing.
    settings.spp = trace::kSamplesPerRound + 300;
    settings.resume = nullptr;
    const AovSet finished = trace::render_scene("grids", settings);
    settings.resume = &finished;
    const AovSet again = trace::render_scene("grids", settings);
    for (std::size_t i = 0; i < finished.channel_names().size(); ++i)
        CHECK(again.plane(i) == finished.plane(i));
    settings.spp = 2 * trace::kSamplesPerRound;
    settings.resume = &half;

    settings.seed = 2;  // a different render cannot continue this one
    CHECK_THROWS_WITH(trace::render_scene("grids", settings), Catch::Contains("aaf:seed"));
}

TEST_CASE("A checkpoint written between rounds resumes to the uninterrupted render", "[trace][resume]") {
    trace::RenderSettings settings;
    settings.width = 20;
    settings.height = 15;
    settings.spp = 3 * trace::kSamplesPerRound;
    settings.checkpoint_interval_s = 1e-9;  // after every round but the last
    std::vector<AovSet> checkpoints;
    std::vector<int> progress;
    settings.on_checkpoint = [&](const AovSet &partial) { checkpoints.push_back(partial); };
    settings.on_progress = [&](int done, int total) {
        CHECK(total == settings.spp);
        progress.push_back(done);
    };
    const AovSet whole = trace::render_scene("grids", settings);
    CHECK(progress == std::vector<int>{1024, 2048, 3072});
    REQUIRE(checkpoints.size() == 2);
    CHECK(std::get<int>(checkpoints[0].attributes.at(attr::kSppDone)) == 1024);
    CHECK(std::get<int>(checkpoints[1].attributes.at(attr::kSppDone)) == 2048);
    CHECK(checkpoints[0].channel("pixel.spp")(10, 10) == 1024.0f);

    // A render killed after its first checkpoint continues from it to the same result.
    trace::RenderSettings resumed = settings;
    resumed.on_checkpoint = nullptr;
    resumed.on_progress = nullptr;
    resumed.resume = &checkpoints[0];
    const AovSet continued = trace::render_scene("grids", resumed);
    for (std::size_t i = 0; i < whole.channel_names().size(); ++i)
        CHECK(continued.plane(i) == whole.plane(i));
}

namespace {

double rms_difference(const std::vector<float> &a, const std::vector<float> &b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    return std::sqrt(sum / double(a.size()));
}

}  // namespace

TEST_CASE("A partial render that ends inside a round resumes with fresh rounds", "[trace][resume]") {
    trace::RenderSettings settings;
    settings.width = 24;
    settings.height = 18;
    settings.spp = 1500;  // one whole round and 476 samples of pass 1
    const AovSet partial = trace::render_scene("grids", settings);
    settings.spp = 3000;
    std::vector<int> progress;
    settings.on_progress = [&](int done, int) { progress.push_back(done); };
    settings.resume = &partial;
    const AovSet resumed = trace::render_scene("grids", settings);
    settings.on_progress = nullptr;
    settings.resume = nullptr;
    CHECK(std::get<int>(resumed.attributes.at(attr::kSppDone)) == 3000);
    CHECK(progress == std::vector<int>{2524, 3000});  // passes 2 and 3, after the partial's 0 and 1
    CHECK(resumed.channel("pixel.spp")(12, 9) == 3000.0f);

    // The new samples are not the partial's over again (which would leave the
    // visibility exactly as it was and double every sum)...
    const std::vector<float> &v_partial = plane(partial, "shadow.V"), &v_resumed = plane(resumed, "shadow.V");
    int changed = 0;
    for (std::size_t i = 0; i < v_partial.size(); ++i) changed += v_partial[i] != v_resumed[i];
    CHECK(changed > 20);
    // ...and the result is as close to a render in one go as a render of another seed.
    const AovSet whole = trace::render_scene("grids", settings);
    settings.seed = 2;
    const AovSet reseeded = trace::render_scene("grids", settings);
    const double resumed_error = rms_difference(v_resumed, plane(whole, "shadow.V"));
    const double seed_error = rms_difference(plane(reseeded, "shadow.V"), plane(whole, "shadow.V"));
    INFO("resumed vs whole " << resumed_error << ", seed 2 vs whole " << seed_error);
    CHECK(resumed_error > 0);
    CHECK(resumed_error < 1.5 * seed_error);
    CHECK(resumed_error < 0.01);
}

TEST_CASE("A partial render of an edited scene is refused", "[trace][resume]") {
    const std::filesystem::path dir = std::filesystem::path(AAF_TEST_BINARY_DIR) / "scratch" / "edited_scene";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "edited.json").string();
    auto write_scene = [&](const char *light_center) {
        std::ofstream(path) << R"({"name": "edited", "camera": {"position": [0, 3, 3], "look_at": [0, 0, 0]},
  "lights": [{"center": )" << light_center
                            << R"(, "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5]}],
  "objects": [{"type": "plane", "size": [6, 6]}, {"type": "box", "min": [-0.3, 0.5, -0.3], "max": [0.3, 0.6, 0.3]}]})";
    };
    write_scene("[0, 3, 0]");
    trace::RenderSettings settings;
    settings.width = 16;
    settings.height = 12;
    settings.spp = trace::kSamplesPerRound;
    const AovSet partial = trace::render_scene(path, settings);
    const auto &hash = std::get<std::string>(partial.attributes.at(attr::kSceneHash));
    CHECK(hash.size() == 16);
    CHECK(hash == std::get<std::string>(trace::render_scene(path, settings).attributes.at(attr::kSceneHash)));

    settings.spp = 2 * trace::kSamplesPerRound;
    settings.resume = &partial;
    settings.resume_source = "partial.exr";
    CHECK_NOTHROW(trace::render_scene(path, settings));
    write_scene("[0.2, 3, 0]");  // same name, seed, size, frame and light kind; the light moved
    CHECK_THROWS_WITH(trace::render_scene(path, settings),
                      Catch::StartsWith("partial.exr: cannot resume: the scene changed"));
}
