// Filtering corrects the user's image: each method replaces only the
// component of the beauty it models, and everything else passes through.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../cli/run_aaf.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"

namespace {

using namespace aaf;
namespace fs = std::filesystem;

trace::RenderSettings small(const std::string &method, int spp, unsigned seed) {
    trace::RenderSettings settings;
    settings.width = 32;
    settings.height = 24;
    settings.spp = spp;
    settings.seed = seed;
    settings.aovs = trace::aov_groups_for_method(method);
    return settings;
}

double rmse_rgb(const AovSet &a, const AovSet &b) {
    double sum = 0;
    for (const char *c : {"R", "G", "B"}) {
        const ConstPlaneView x = a.channel(c), y = b.channel(c);
        for (int j = 0; j < a.height(); ++j)
            for (int i = 0; i < a.width(); ++i) sum += double(x(i, j) - y(i, j)) * double(x(i, j) - y(i, j));
    }
    return std::sqrt(sum / (3.0 * double(a.pixel_count())));
}

}  // namespace

TEST_CASE(
    "Light the AOVs do not model, added to R,G,B, survives aaf, maaf, gaussian, isg-shadow and ratio, "
    "which replace only what they model",
    "[methods][beauty]") {
    for (const char *name : {"aaf", "maaf", "gaussian", "isg-shadow", "ratio"}) {
        INFO("method " << name);
        const Method &method = find_method(name);
        const AovSet render = trace::render_scene("grids", small(name, 4, 3));
        AovSet lit = render;
        for (const char *c : {"R", "G", "B"}) {
            PlaneView plane = lit.channel(c);
            for (int y = 0; y < plane.height; ++y)
                for (int x = 0; x < plane.width; ++x) plane(x, y) += 0.05f;
        }
        const AovSet out = filter_aovs(method, render, ChannelMap{}, method.default_parameters());
        const AovSet out_lit = filter_aovs(method, lit, ChannelMap{}, method.default_parameters());
        double worst = 0, mean = 0;
        for (const char *c : {"R", "G", "B"})
            for (int y = 0; y < out.height(); ++y)
                for (int x = 0; x < out.width(); ++x) {
                    const double kept = double(out_lit.channel(c)(x, y)) - double(out.channel(c)(x, y));
                    worst = std::max(worst, std::fabs(kept - 0.05));
                    mean += kept / (3.0 * double(out.pixel_count()));
                }
        CHECK(mean == Approx(0.05).margin(1e-3));
        CHECK(worst < 1e-4);
        // And the method did replace its component: the noise it models changed.
        CHECK(rmse_rgb(out, render) > 1e-3);
    }
}

TEST_CASE(
    "aaf filter ratio's R,G,B on livingroom at 2 rays per light are at least 2x closer to the reference "
    "beauty than the noisy beauty",
    "[methods][beauty]") {
    trace::RenderSettings noisy = small("ratio", 2, 2), reference = small("ratio", 256, 9);
    noisy.width = reference.width = 80;
    noisy.height = reference.height = 60;
    const AovSet two = trace::render_scene("livingroom", noisy);
    const AovSet ref = trace::render_scene("livingroom", reference);
    const Method &ratio = find_method("ratio");
    const AovSet out = filter_aovs(ratio, two, ChannelMap{}, ratio.default_parameters());
    const double before = rmse_rgb(two, ref), after = rmse_rgb(out, ref);
    INFO("noisy beauty RMSE " << before << ", ratio " << after);
    CHECK(2 * after <= before);
}

TEST_CASE("aaf compare OUT REF measures what every registered method estimates, by role, without --channels",
          "[methods][beauty][cli]") {
    const fs::path dir = aaf_test::scratch_dir("compare_by_role");
    for (const Method *method : methods()) {
        const std::string name = method->info().name;
        if (name.rfind("toy", 0) == 0) continue;  // the test plug-ins are not in the aaf executable
        INFO("method " << name);
        const std::string scene = name == "isg-dof" ? "gallery" : name == "maaf6" ? "spheres" : "grids";
        const fs::path in = dir / (name + ".in.exr"), ref = dir / (name + ".ref.exr"),
                       out = dir / (name + ".out.exr");
        io::write_aovs(trace::render_scene(scene, small(name, 2, 4)), in.string());
        io::write_aovs(trace::render_scene(scene, small(name, 16, 5)), ref.string());
        const auto filtered = aaf_test::run_aaf("filter " + name + " " + in.string() + " -o " + out.string() +
                                                " --progress none");
        REQUIRE(filtered.exit_code == 0);
        const auto compared = aaf_test::run_aaf("compare " + out.string() + " " + ref.string() + " --json");
        REQUIRE(compared.exit_code == 0);
        const nlohmann::json result = nlohmann::json::parse(compared.output);
        const auto &[estimate, reference_role] = method->info().compared;
        std::vector<std::string> expected;
        for (std::size_t c = 0; c < role_info(estimate).channels.size(); ++c) {
            const std::string &tested = role_info(estimate).channels[c];
            const std::string &against = role_info(reference_role).channels[c];
            expected.push_back(tested == against ? tested : tested + "=" + against);
        }
        CHECK(result.at("channels").get<std::vector<std::string>>() == expected);
    }
}

TEST_CASE(
    "Another renderer's beauty is corrected through its pass of the key light by aaf and gaussian, and "
    "other light added to it survives",
    "[methods][beauty]") {
    for (const char *name : {"aaf", "gaussian"}) {
        INFO("method " << name);
        const Method &method = find_method(name);
        AovSet foreign = trace::render_scene("grids", small(name, 4, 3));
        foreign.attributes.erase(attr::kBeauty);  // not the tracer's beauty
        // Its key light alone, as a light group would hold it: here all of its direct light.
        const std::vector<std::string> &pass = role_info(Role::KeyLight).channels;
        for (std::size_t c = 0; c < 3; ++c) {
            PlaneView key = foreign.add_channel(pass[c]);
            const ConstPlaneView beauty = foreign.channel(role_info(Role::Beauty).channels[c]);
            for (int y = 0; y < key.height; ++y)
                for (int x = 0; x < key.width; ++x) key(x, y) = beauty(x, y);
        }
        AovSet lit = foreign;
        for (const char *c : {"R", "G", "B"}) {
            PlaneView plane = lit.channel(c);
            for (int y = 0; y < plane.height; ++y)
                for (int x = 0; x < plane.width; ++x) plane(x, y) += 0.05f;
        }
        const AovSet out = filter_aovs(method, foreign, ChannelMap{}, method.default_parameters());
        const AovSet out_lit = filter_aovs(method, lit, ChannelMap{}, method.default_parameters());
        double worst = 0;
        for (const char *c : {"R", "G", "B"})
            for (int y = 0; y < out.height(); ++y)
                for (int x = 0; x < out.width(); ++x)
                    worst = std::max(worst, std::fabs(double(out_lit.channel(c)(x, y)) -
                                                      double(out.channel(c)(x, y)) - 0.05));
        CHECK(worst < 1e-4);
        CHECK(rmse_rgb(out, foreign) > 1e-3);  // the pass was filtered and swapped in
    }
}

TEST_CASE("Filtering a filtered frame again keeps its R,G,B and says so, never correcting twice",
          "[methods][beauty]") {
    const Method &aaf = find_method("aaf");
    const AovSet render = trace::render_scene("grids", small("aaf", 4, 3));
    const AovSet once = filter_aovs(aaf, render, ChannelMap{}, aaf.default_parameters());
    CHECK(once.attributes.count(attr::kBeauty) == 0);
    const FilterPlan plan = prepare_filter(aaf, aaf.default_parameters(), once, ChannelMap{});
    CHECK_THAT(plan.note, Catch::Contains("R,G,B left as rendered"));
    const AovSet twice = run_filter(plan, once);
    for (const char *c : {"R", "G", "B"})
        CHECK(once.plane(once.index_of(c)) == twice.plane(twice.index_of(c)));
}
