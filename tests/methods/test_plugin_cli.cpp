// The test plug-ins linked into the `aaf` front end as `aaf_with_toy`: the
// toy method (toy_box_blur.cpp) declares a role, toy_hit, that the toy
// tracer group (toy_hit_group.cpp) writes. Registering each in its own file
// was all it took to get a render group, a filter subcommand, help,
// parameter checking, a `--map` key and a line in `aaf info` with its recipe.
#include <catch2/catch.hpp>

#include "../cli/run_aaf.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/io/exr_io.h"

using namespace aaf_test;

namespace {

/// A 5x4 file with a ramp along x in a channel called `mine` and nothing else.
std::string ramp_file(const fs::path &dir) {
    aaf::AovSet aovs(5, 4);
    aaf::PlaneView v = aovs.add_channel("mine");
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) v(x, y) = float(x);
    const std::string path = (dir / "ramp.exr").string();
    aaf::io::write_aovs(aovs, path);
    return path;
}

}  // namespace

TEST_CASE("A plug-in method needing a plug-in group's new role: help, render, info with its recipe, filter",
          "[methods][cli]") {
    const fs::path dir = scratch_dir("plugin_cli");
    const std::string ramp = ramp_file(dir), output = (dir / "out.exr").string();
    const std::string rendered = (dir / "toy.exr").string(), plain = (dir / "plain.exr").string();

    const RunResult help = run_aaf("filter --help", AAF_TOY_EXECUTABLE);
    CHECK(help.exit_code == 0);
    CHECK_THAT(help.output, Catch::Contains("toy_box") && Catch::Contains("Test plug-in") &&
                                Catch::Contains("toy_box: reads toy_hit"));
    const RunResult method_help = run_aaf("filter toy_box --help", AAF_TOY_EXECUTABLE);
    CHECK_THAT(method_help.output, Catch::Contains("--radius") && Catch::Contains("[0, 16]"));

    // The group writes the method's role under the name the method declared.
    const std::string size = " --width 8 --height 6 --spp 1 --progress none -o ";
    REQUIRE(run_aaf("render grids --aovs toy_hits" + size + rendered, AAF_TOY_EXECUTABLE).exit_code == 0);
    REQUIRE(run_aaf("render grids --aovs shadow" + size + plain, AAF_TOY_EXECUTABLE).exit_code == 0);
    const aaf::AovSet toy = aaf::io::read_aovs(rendered);
    REQUIRE(toy.has_channel("toy.hit"));

    CHECK_THAT(run_aaf("info " + rendered, AAF_TOY_EXECUTABLE).output, Catch::Contains("toy_box  ready"));
    const RunResult info = run_aaf("info " + plain, AAF_TOY_EXECUTABLE);
    CHECK_THAT(info.output, Catch::Contains("toy_box  missing") &&
                                Catch::Contains("- toy_hit [toy.hit]: aaf render SCENE --aovs toy_hits"));

    REQUIRE(run_aaf("filter toy_box " + rendered + " -o " + output + " --radius 1", AAF_TOY_EXECUTABLE)
                .exit_code == 0);
    const aaf::AovSet blurred = aaf::io::read_aovs(output);
    // A 3x3 box at an interior pixel: the mean of toy.hit over its neighbours.
    float sum = 0;
    for (int y = 1; y <= 3; ++y)
        for (int x = 2; x <= 4; ++x) sum += toy.channel("toy.hit")(x, y);
    CHECK(blurred.channel("toy.blurred")(3, 2) == Approx(sum / 9));
    CHECK(blurred.channel("toy.hit")(3, 2) == toy.channel("toy.hit")(3, 2));  // the input is kept as it was

    // The new role is a --map key like the contract's own.
    REQUIRE(run_aaf("filter toy_box " + ramp + " --map toy_hit=mine -o " + output, AAF_TOY_EXECUTABLE)
                .exit_code == 0);
    const aaf::AovSet out = aaf::io::read_aovs(output);
    // A 3x3 box over a ramp along x: the interior keeps the ramp, the left edge averages 0 and 1.
    CHECK(out.channel("toy.blurred")(2, 1) == Approx(2.0f));
    CHECK(out.channel("toy.blurred")(0, 0) == Approx(0.5f));

    const RunResult bad =
        run_aaf("filter toy_box " + rendered + " -o " + output + " --radius 17", AAF_TOY_EXECUTABLE);
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.output, Catch::Contains("'radius'") && Catch::Contains("[0, 16]"));
    CHECK(std::count(bad.output.begin(), bad.output.end(), '\n') == 1);

    // The shipped tool has neither: the plug-ins live in the test build only.
    CHECK(run_aaf("filter toy_box " + rendered + " -o " + output).exit_code == 2);
    CHECK(run_aaf("render grids --aovs toy_hits" + size + output).exit_code == 2);
}
