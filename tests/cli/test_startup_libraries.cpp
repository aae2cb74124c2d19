#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>
#include <string>

#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

/// The shared libraries whose initialisers a run of `aaf ARGS` called, one
/// "calling init: PATH" line each in the dynamic loader's LD_DEBUG=libs log:
/// what a command pays for at start-up, or on first use of a module.
std::string initialised_libraries(const std::string &args) {
    const aaf_test::RunResult run = run_aaf(args, "LD_DEBUG=libs " + std::string(AAF_EXECUTABLE));
    INFO(run.output);
    REQUIRE(run.exit_code == 0);
    std::istringstream lines(run.output);
    std::string line, libraries;
    while (std::getline(lines, line))
        if (line.find("calling init:") != std::string::npos)
            libraries += line.substr(line.find(':', line.find("init")) + 1) + "\n";
    return libraries;
}

bool loads(const std::string &libraries, const std::string &name) {
    return libraries.find("/" + name) != std::string::npos;
}

}  // namespace

TEST_CASE(
    "start-up: a one-frame filter and --version load neither OpenImageIO nor OpenColorIO, a sequence "
    "loads OpenImageIO's utility library alone",
    "[cli][startup]") {
    const fs::path dir = scratch_dir("startup_libraries");
    aaf::trace::RenderSettings settings;
    settings.width = 16;
    settings.height = 12;
    settings.spp = 2;
    for (int frame = 1; frame <= 2; ++frame)
        aaf::io::write_aovs(aaf::trace::render_scene("grids", settings),
                            (dir / ("in.000" + std::to_string(frame) + ".exr")).string());

    const std::string version = initialised_libraries("--version");
    const std::string one_frame = initialised_libraries("filter aaf " + (dir / "in.0001.exr").string() +
                                                        " -o " + (dir / "out.exr").string());
    // The loader's log is read at all: the C library is always initialised.
    REQUIRE(loads(version, "libc.so"));
    for (const std::string *libraries : {&version, &one_frame}) {
        INFO(*libraries);
        CHECK_FALSE(loads(*libraries, "libOpenImageIO"));
        CHECK_FALSE(loads(*libraries, "libOpenColorIO"));
        CHECK_FALSE(loads(*libraries, "libaaf_formats.so"));
        CHECK_FALSE(loads(*libraries, "libaaf_sequences.so"));
    }

    const std::string sequence =
        initialised_libraries("filter aaf " + (dir / "in.####.exr").string() + " -o " +
                              (dir / "out.####.exr").string() + " --frames 1-2");
    INFO(sequence);
    CHECK(fs::exists(dir / "out.0002.exr"));
    CHECK(loads(sequence, "libaaf_sequences.so"));
    CHECK(loads(sequence, "libOpenImageIO_Util"));
    CHECK_FALSE(loads(sequence, "libOpenImageIO.so"));
    CHECK_FALSE(loads(sequence, "libOpenColorIO"));
}
