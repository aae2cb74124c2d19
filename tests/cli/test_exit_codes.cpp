// The exit codes of README's "Errors and exit codes", one table over every command:
// 0 success, 2 usage (a bad option or value), 3 input (a file, channel or
// header problem), 4 a failed compare check.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "flat_image.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;

namespace {

struct Case {
    std::string args;
    int code;
};

/// A scratch folder with a 4x4 flat image, another of 0.6 and a 16x12 render of grids.
std::string exit_code_inputs(const std::string &name) {
    const fs::path dir = aaf_test::scratch_dir(name);
    aaf_test::write_flat(dir / "flat.exr", 0.5f);
    aaf_test::write_flat(dir / "other.exr", 0.6f);
    REQUIRE(run_aaf("render grids -o " + (dir / "noisy.exr").string() + " --width 16 --height 12 --spp 2")
                .exit_code == 0);
    return dir.string() + "/";
}

/// Runs each case: its exit code, and one error line for usage and input errors
/// (a failed check names the pair instead).
void check_exit_codes(const std::vector<Case> &cases) {
    for (const Case &c : cases) {
        const auto run = run_aaf(c.args);
        INFO("aaf " << c.args << "\n" << run.output);
        CHECK(run.exit_code == c.code);
        if (c.code == 2 || c.code == 3) CHECK_THAT(run.output, Catch::StartsWith("aaf: error: "));
    }
}

}  // namespace

TEST_CASE("exit codes: render exit with the documented codes (0, 2 usage, 3 input, 4 check)", "[cli][exit]") {
    const std::string d = exit_code_inputs("exit_codes_render");
    check_exit_codes({
        {"render grids -o " + d + "r.exr --width 0", 2},
        {"render grids -o " + d + "r.exr --spp x", 2},
        {"render grids -o " + d + "r.exr --adaptive --mu 0", 2},
        {"render nosuchscene -o " + d + "r.exr", 3},
        {"render grids -o " + d + "r.png", 2},
    });
}

TEST_CASE("exit codes: plan exit with the documented codes (0, 2 usage, 3 input, 4 check)", "[cli][exit]") {
    const std::string d = exit_code_inputs("exit_codes_plan");
    check_exit_codes({
        {"plan " + d + "noisy.exr -o " + d + "p.exr --mu 0", 2},
        {"plan " + d + "missing.exr -o " + d + "p.exr", 3},
        {"plan " + d + "noisy.exr -o " + d + "p.exr", 0},
        {"plan " + d + "noisy.exr -o " + d + "p.tif", 2},
    });
}

TEST_CASE("exit codes: filter exit with the documented codes (0, 2 usage, 3 input, 4 check)", "[cli][exit]") {
    const std::string d = exit_code_inputs("exit_codes_filter");
    check_exit_codes({
        {"filter nosuchmethod " + d + "noisy.exr -o " + d + "f.exr", 2},
        {"filter aaf " + d + "noisy.exr -o " + d + "f.exr --mu 0", 2},
        {"filter aaf " + d + "noisy.exr -o " + d + "f.exr --mu abc", 2},
        {"filter aaf " + d + "noisy.exr -o " + d + "f.exr --filter 3d", 2},
        {"filter aaf " + d + "noisy.exr -o " + d + "f.exr --map nosuchrole=X", 2},
        {"filter gaussian " + d + "noisy.exr -o " + d + "f.exr --sigma -1", 2},
        {"filter aaf " + d + "missing.exr -o " + d + "f.exr", 3},
        {"filter aaf " + d + "flat.exr -o " + d + "f.exr", 3},  // no AOVs
        {"filter aaf " + d + "noisy.exr -o " + d + "noisy.exr", 3},
        {"filter aaf " + d + "noisy.exr -o " + d + "f.exr", 0},
        {"filter aaf " + d + "noisy.exr -o " + d + "f.jpg", 2},
    });
}

TEST_CASE("exit codes: compare exit with the documented codes (0, 2 usage, 3 input, 4 check)",
          "[cli][exit]") {
    const std::string d = exit_code_inputs("exit_codes_compare");
    check_exit_codes({
        {"compare " + d + "flat.exr " + d + "other.exr --metric nosuch", 2},
        {"compare " + d + "flat.exr " + d + "other.exr --peak 0", 2},
        {"compare " + d + "flat.exr " + d + "other.exr --crop 0,0,0,1", 2},
        {"compare " + d + "missing.exr " + d + "other.exr", 3},
        {"compare " + d + "flat.exr " + d + "noisy.exr", 3},  // sizes differ
        {"compare " + d + "flat.exr " + d + "other.exr --channels nosuch", 3},
        {"compare " + d + "flat.exr " + d + "other.exr --fail-above rmse=0.01", 4},
        {"compare " + d + "flat.exr " + d + "other.exr", 0},
    });
}

TEST_CASE(
    "exit codes: info, preview, analyze and an unknown command exit with the documented codes (0, 2 usage, 3 "
    "input, 4 check)",
    "[cli][exit]") {
    const std::string d = exit_code_inputs("exit_codes_info");
    check_exit_codes({
        {"frobnicate", 2},
        {"info " + d + "missing.exr", 3},
        {"info " + d + "noisy.exr", 0},
        {"info", 2},
        {"preview " + d + "noisy.exr -o " + d + "p.gif", 2},
        {"preview " + d + "noisy.exr -o " + d + "p.png --exposure abc", 2},
        {"preview " + d + "noisy.exr -o " + d + "p.png --ocio-config " + d + "missing.ocio", 3},
        {"preview " + d + "noisy.exr -o " + d + "p.png --channels nosuch.V", 3},
        {"preview " + d + "missing.exr -o " + d + "p.png", 3},
        {"preview " + d + "noisy.exr -o " + d + "p.png", 0},
        {"preview " + d + "noisy.exr -o " + d + "p.jpg", 0},
        {"analyze wedge --smin 2 --smax 1", 2},
        {"analyze nosuch", 2},
    });
}

TEST_CASE("preview: the output's extension picks its format", "[cli][preview]") {
    const fs::path dir = aaf_test::scratch_dir("preview_format");
    aaf_test::write_flat(dir / "flat.exr", 0.5f);
    REQUIRE(run_aaf("preview " + (dir / "flat.exr").string() + " -o " + (dir / "x.jpg").string()).exit_code ==
            0);
    REQUIRE(run_aaf("preview " + (dir / "flat.exr").string() + " -o " + (dir / "x.png").string()).exit_code ==
            0);
    auto magic = [](const fs::path &path) {
        std::ifstream in(path, std::ios::binary);
        unsigned char bytes[2] = {0, 0};
        in.read(reinterpret_cast<char *>(bytes), 2);
        return (unsigned(bytes[0]) << 8) | bytes[1];
    };
    CHECK(magic(dir / "x.jpg") == 0xFFD8u);  // JPEG SOI
    CHECK(magic(dir / "x.png") == 0x8950u);  // \x89P
}

TEST_CASE("warnings: options without effect are named and filter --help lists every method's options",
          "[cli][exit]") {
    const fs::path dir = aaf_test::scratch_dir("no_effect_warnings");
    const auto render = run_aaf("render grids -o " + (dir / "r.exr").string() +
                                " --width 8 --height 6 --spp 1 --mu 4 --max-spp 9");
    CHECK(render.exit_code == 0);
    CHECK_THAT(render.output, Catch::Contains("warning: --mu has no effect without --adaptive") &&
                                  Catch::Contains("warning: --max-spp has no effect without --adaptive"));
    const auto adaptive = run_aaf("render grids -o " + (dir / "a.exr").string() +
                                  " --width 8 --height 6 --spp 1 --adaptive --mu 4 --max-spp 9");
    CHECK(adaptive.exit_code == 0);
    CHECK_THAT(adaptive.output, !Catch::Contains("no effect"));
    aaf_test::write_flat(dir / "a.exr", 0.5f);
    const std::string pair = (dir / "a.exr").string() + " " + (dir / "a.exr").string();
    CHECK_THAT(run_aaf("compare " + pair + " --ppd 30").output,
               Catch::Contains("warning: --ppd has no effect without a flip metric"));
    CHECK_THAT(run_aaf("compare " + pair + " --ppd 30 --metric flip").output, !Catch::Contains("warning"));
    const std::string png = " -o " + (dir / "a.png").string();
    CHECK_THAT(run_aaf("preview " + (dir / "a.exr").string() + png + " --range 0,1").output,
               Catch::Contains("warning: --range has no effect without --false-colour"));
    CHECK_THAT(
        run_aaf("preview " + (dir / "a.exr").string() + png + " --channels R --false-colour --exposure 2")
            .output,
        Catch::Contains("warning: --exposure has no effect with --false-colour"));
    const auto help = run_aaf("filter --help");
    CHECK(help.exit_code == 0);
    CHECK_THAT(help.output, Catch::Contains("--mu") && Catch::Contains("--normal-threshold") &&
                                Catch::Contains("--sigma") && Catch::Contains("gaussian"));
}
