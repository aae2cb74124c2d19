// The test AOV group (toy_hit_group.cpp), registered from its own file, in
// the library's registry and in the `aaf` front end built with it (aaf_with_toy).
#include <algorithm>
#include <catch2/catch.hpp>

#include "../cli/run_aaf.h"
#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"

using namespace aaf_test;

TEST_CASE("An AOV group registered from its own file is rendered, named by --aovs and given its options",
          "[methods][trace][cli]") {
    namespace trace = aaf::trace;
    // The registry: parsed by name and in "all" (it traces nothing of its own), after the built-ins.
    CHECK(trace::parse_aov_groups("toy_hits") == trace::AovGroups{"toy_hits"});
    CHECK(trace::parse_aov_groups("all").contains("toy_hits"));
    CHECK(trace::aov_group_table().back().name == "toy_hits");
    CHECK(trace::find_aov_group("toy_hits").parameters.at(0).option_name() == "--toy-hit-value");

    // A render with it writes its channel, with its parameter's value.
    trace::RenderSettings settings;
    settings.width = 16;
    settings.height = 12;
    settings.spp = 1;
    settings.aovs = trace::parse_aov_groups("shadow,toy_hits");
    settings.group_parameters.of("toy_hits").set("toy_hit_value", 3.0);
    const aaf::AovSet aovs = trace::render_scene("grids", settings);
    REQUIRE(aovs.has_channel("toy.hit"));
    float lowest = 1e9f, highest = -1e9f;
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            lowest = std::min(lowest, aovs.channel("toy.hit")(x, y));
            highest = std::max(highest, aovs.channel("toy.hit")(x, y));
        }
    CHECK(lowest == 3.0f);  // every pixel of grids sees the ground or a grid
    CHECK(highest == 3.0f);
    CHECK_FALSE(trace::render_scene("grids",
                                    [&] {
                                        trace::RenderSettings without = settings;
                                        without.aovs = {"shadow"};
                                        return without;
                                    }())
                    .has_channel("toy.hit"));

    // The front end built with it: --aovs help, its option, a render's file.
    const RunResult help = run_aaf("render --help", AAF_TOY_EXECUTABLE);
    CHECK_THAT(help.output, Catch::Contains(", ratio_estimators, toy_hits)") &&
                                Catch::Contains("--toy-hit-value") &&
                                Catch::Contains("With --aovs toy_hits: the value written at a hit"));
    // Every group is named in the --aovs help.
    std::string aovs_help = help.output.substr(help.output.find("--aovs TEXT"));
    aovs_help = aovs_help.substr(0, aovs_help.find('\n'));
    std::replace_if(
        aovs_help.begin(), aovs_help.end(),
        [](char c) { return c == ',' || c == '(' || c == ')' || c == ';'; }, ' ');
    for (const trace::AovGroupInfo &group : trace::aov_group_table())
        CHECK_THAT(aovs_help + " ", Catch::Contains(" " + group.name + " "));
    const fs::path dir = scratch_dir("aov_group_plugin");
    const std::string output = (dir / "toy.exr").string();
    const RunResult render = run_aaf(
        "render grids --width 8 --height 6 --spp 1 --progress none --aovs toy_hits "
        "--toy-hit-value 2 -o " +
            output,
        AAF_TOY_EXECUTABLE);
    REQUIRE(render.exit_code == 0);
    const aaf::AovSet written = aaf::io::read_aovs(output);
    REQUIRE(written.has_channel("toy.hit"));
    CHECK(written.channel("toy.hit")(4, 5) == 2.0f);
    CHECK_THAT(std::get<std::string>(written.attributes.at("aaf:provenance:parameters")),
               Catch::Contains("aovs=toy_hits") && Catch::Contains("toy_hit_value=2"));
    // Its option without the group: a warning; a value out of its range: a usage error naming the option.
    CHECK_THAT(
        run_aaf("render grids --width 8 --height 6 --spp 1 --progress none --toy-hit-value 2 -o " + output,
                AAF_TOY_EXECUTABLE)
            .output,
        Catch::Contains("aaf: warning: --toy-hit-value has no effect without the toy_hits group"));
    const RunResult bad =
        run_aaf("render grids --aovs toy_hits --toy-hit-value -1 -o " + output, AAF_TOY_EXECUTABLE);
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.output, Catch::Contains("--toy-hit-value") && Catch::Contains(">= 0"));
    // The shipped tool has no such group.
    CHECK(run_aaf("render grids --aovs toy_hits -o " + output).exit_code == 2);
}
