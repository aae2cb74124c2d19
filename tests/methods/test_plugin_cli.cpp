// The test plug-in (toy_box_blur.cpp) linked into the `aaf` front end as
// `aaf_with_toy`: registering it was all it took to get a subcommand, help,
// parameter checking and a line in `aaf info`.
#include <catch2/catch.hpp>

#include "../cli/run_aaf.h"
#include "aaf/core/aov_contract.h"
#include "aaf/io/exr_io.h"

using namespace aaf_test;

namespace {

/// A 5x4 file with a visibility ramp and nothing else.
std::string ramp_file(const fs::path &dir) {
    aaf::AovSet aovs(5, 4);
    aaf::PlaneView v = aovs.add_channel("shadow.V");
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) v(x, y) = float(x);
    const std::string path = (dir / "ramp.exr").string();
    aaf::io::write_aovs(aovs, path);
    return path;
}

}  // namespace

TEST_CASE("A registered plug-in gets its filter subcommand, help and info line", "[methods][cli]") {
    const fs::path dir = scratch_dir("plugin_cli");
    const std::string input = ramp_file(dir), output = (dir / "out.exr").string();

    const RunResult help = run_aaf("filter --help", AAF_TOY_EXECUTABLE);
    CHECK(help.exit_code == 0);
    CHECK_THAT(help.output, Catch::Contains("toy_box") && Catch::Contains("Test plug-in") &&
                                Catch::Contains("toy_box: reads visibility"));
    const RunResult method_help = run_aaf("filter toy_box --help", AAF_TOY_EXECUTABLE);
    CHECK_THAT(method_help.output, Catch::Contains("--radius") && Catch::Contains("[0, 16]"));

    const RunResult info = run_aaf("info " + input, AAF_TOY_EXECUTABLE);
    CHECK_THAT(info.output, Catch::Contains("toy_box  ready") && Catch::Contains("aaf      missing") &&
                                Catch::Contains("- d1 [shadow.d1]: aaf render SCENE --aovs shadow"));

    const RunResult run =
        run_aaf("filter toy_box " + input + " -o " + output + " --radius 1", AAF_TOY_EXECUTABLE);
    REQUIRE(run.exit_code == 0);
    const aaf::AovSet out = aaf::io::read_aovs(output);
    // A 3x3 box over a ramp along x: the interior keeps the ramp, the left edge averages 0 and 1.
    CHECK(out.channel("aaf.V")(2, 1) == Approx(2.0f));
    CHECK(out.channel("aaf.V")(0, 0) == Approx(0.5f));
    CHECK(out.channel("shadow.V")(0, 0) == 0.0f);  // the input channel is kept as it was

    const RunResult bad =
        run_aaf("filter toy_box " + input + " -o " + output + " --radius 17", AAF_TOY_EXECUTABLE);
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.output, Catch::Contains("'radius'") && Catch::Contains("[0, 16]"));
    CHECK(std::count(bad.output.begin(), bad.output.end(), '\n') == 1);

    // The shipped tool has no such method: the plug-in lives in the test build only.
    CHECK(run_aaf("filter toy_box " + input + " -o " + output).exit_code == 2);
}
