// Bad command lines and bad ranges for compare, filter, preview, plan and info:
// each is refused with the documented exit code and one `aaf: error:` line,
// leaving no output and the inputs as they were.
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "aaf/io/exr_io.h"
#include "flat_image.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;
using aaf_test::write_flat;

namespace {

std::string bytes_of(const fs::path &path) {
    std::stringstream text;
    text << std::ifstream(path, std::ios::binary).rdbuf();
    return text.str();
}

/// True when `output` is exactly one line, `aaf: error: ...`.
bool one_error_line(const std::string &output) {
    return output.rfind("aaf: error: ", 0) == 0 && output.find('\n') == output.size() - 1;
}

/// The names in `dir`, hidden temporaries included.
std::vector<std::string> names_in(const fs::path &dir) {
    std::vector<std::string> names;
    for (const auto &entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// The largest resident set any finished child of this process has had, MB.
double children_peak_rss_mb() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    return double(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

/// `aaf` under a 2 GB address-space limit: a run that would materialise a
/// huge range fails instead of exhausting the test machine.
const std::string kLimitedAaf = std::string("ulimit -v 2000000; ") + AAF_EXECUTABLE;

}  // namespace

TEST_CASE("compare refuses a crop that wraps past INT_MAX, with and without a heatmap",
          "[cli][reliability]") {
    const fs::path dir = scratch_dir("reliability_crop_overflow");
    write_flat(dir / "a.exr", 0.5f);
    write_flat(dir / "b.exr", 0.25f);
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    const std::string a_bytes = bytes_of(a), b_bytes = bytes_of(b);
    const std::vector<std::string> before = names_in(dir);
    for (const std::string &heatmap : {std::string(), " --heatmap " + (dir / "hm.png").string()}) {
        INFO(heatmap);
        const auto result = run_aaf("compare " + a + " " + b + " --crop 2147483600,0,100,10" + heatmap);
        CHECK(result.exit_code == 3);  // the crop lies outside these images: an input error
        CHECK(one_error_line(result.output));
        CHECK_THAT(result.output, Catch::Contains(a + " vs " + b) && Catch::Contains("outside"));
        CHECK_THAT(result.output, !Catch::Contains("nan"));
        CHECK(names_in(dir) == before);  // no heatmap, no temporary
    }
    CHECK(bytes_of(a) == a_bytes);
    CHECK(bytes_of(b) == b_bytes);
}

TEST_CASE("compare refuses a crop spec with no area or not four integers as a usage error",
          "[cli][reliability]") {
    const fs::path dir = scratch_dir("reliability_crop_usage");
    write_flat(dir / "a.exr", 0.5f);
    write_flat(dir / "b.exr", 0.25f);
    const std::string pair = (dir / "a.exr").string() + " " + (dir / "b.exr").string();
    for (const char *crop : {"0,0,0,4", "0,0,4,-1", "0,0,-5,2", "1,2,3", "0,0,99999999999,1", "a,b,c,d"}) {
        INFO(crop);
        const auto result = run_aaf("compare " + pair + " --crop " + crop);
        CHECK(result.exit_code == 2);
        CHECK(one_error_line(result.output));
    }
    // A negative corner is a place outside the image: an input error like any other.
    const auto outside = run_aaf("compare " + pair + " --crop -1,0,2,2");
    CHECK(outside.exit_code == 3);
    CHECK(one_error_line(outside.output));
    // Inside: measured.
    CHECK(run_aaf("compare " + pair + " --crop 1,1,3,3").exit_code == 0);
}

TEST_CASE(
    "a two-billion-frame range is streamed: render, filter and compare stop at the first failing frame "
    "in bounded memory",
    "[cli][reliability][sequence]") {
    const fs::path dir = scratch_dir("reliability_huge_range");
    const std::string in = (dir / "in.####.exr").string(), out = (dir / "out.####.exr").string();
    const auto filtered =
        run_aaf("filter aaf " + in + " -o " + out + " --frames 1-2000000000 --progress none", kLimitedAaf);
    CHECK(filtered.exit_code == 3);  // frame 1 does not exist
    CHECK(one_error_line(filtered.output));
    CHECK_THAT(filtered.output, Catch::Contains("in.0001.exr"));

    const auto compared = run_aaf(
        "compare " + in + " " + (dir / "ref.####.exr").string() + " --frames 1-2000000000", kLimitedAaf);
    CHECK(compared.exit_code == 3);
    CHECK(one_error_line(compared.output));
    CHECK_THAT(compared.output, Catch::Contains("in.0001.exr"));

    // Frame 1 renders, then cannot be written into a folder that does not exist.
    const std::string scene = std::string(AAF_SCENE_DIR) + "/grids.json";
    const auto rendered = run_aaf("render " + scene + " -o " + (dir / "missing" / "f.####.exr").string() +
                                      " --frames 1-2000000000 --width 8 --height 8 --spp 1 --progress none",
                                  kLimitedAaf);
    CHECK(rendered.exit_code == 3);
    CHECK(one_error_line(rendered.output));
    CHECK_THAT(rendered.output, Catch::Contains("f.0001.exr"));

    CHECK(children_peak_rss_mb() < 200.0);  // 2e9 frame numbers alone would be 8 GB
    CHECK(names_in(dir).empty());
}

TEST_CASE("a frame number past the int range is one usage line naming --frames, not 'stoi'",
          "[cli][reliability][sequence]") {
    const fs::path dir = scratch_dir("reliability_frames_overflow");
    const std::string in = (dir / "in.####.exr").string(), out = (dir / "out.####.exr").string();
    for (const std::string &command :
         {"filter aaf " + in + " -o " + out, "compare " + in + " " + (dir / "ref.####.exr").string()}) {
        INFO(command);
        const auto result = run_aaf(command + " --frames 1-99999999999");
        CHECK(result.exit_code == 2);
        CHECK(one_error_line(result.output));
        CHECK_THAT(result.output, Catch::StartsWith("aaf: error: --frames: ") &&
                                      Catch::Contains("out of range") && !Catch::Contains("stoi"));
    }
    CHECK(names_in(dir).empty());
}

TEST_CASE("an empty --frames is a usage error, not every frame on disk", "[cli][reliability][sequence]") {
    const fs::path dir = scratch_dir("reliability_frames_empty");
    write_flat(dir / "in.0001.exr", 0.5f);
    write_flat(dir / "ref.0001.exr", 0.5f);
    const std::string in = (dir / "in.####.exr").string();
    const std::vector<std::string> before = names_in(dir);
    for (const std::string &command : {"filter gaussian " + in + " -o " + (dir / "out.####.exr").string(),
                                       "compare " + in + " " + (dir / "ref.####.exr").string()}) {
        INFO(command);
        const auto result = run_aaf(command + " --frames ''");
        CHECK(result.exit_code == 2);
        CHECK(one_error_line(result.output));
        CHECK_THAT(result.output, Catch::Contains("--frames"));
    }
    CHECK(names_in(dir) == before);
}

TEST_CASE("invalid option values of filter, compare, preview and plan exit 2 with one line",
          "[cli][reliability]") {
    const fs::path dir = scratch_dir("reliability_option_values");
    write_flat(dir / "a.exr", 0.5f);
    write_flat(dir / "b.exr", 0.25f);
    write_flat(dir / "in.0001.exr", 0.5f);
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    const std::string out = (dir / "out.exr").string(), png = (dir / "out.png").string();
    const std::string in_seq = (dir / "in.####.exr").string(), out_seq = (dir / "out.####.exr").string();
    const std::vector<std::string> before = names_in(dir);
    const std::vector<std::string> commands = {
        "filter aaf " + a + " -o " + out + " --mu 0",
        "filter aaf " + a + " -o " + out + " --alpha 2",
        "filter aaf " + a + " -o " + out + " --map nosuchrole=X",
        "filter aaf " + a + " -o " + out + " --threads -1",
        "filter aaf " + in_seq + " -o " + out_seq + " --frames 3-1",
        "compare " + a + " " + b + " --metric bogus",
        "compare " + a + " " + b + " --ppd 0",
        "compare " + a + " " + b + " --ppd nan --metric flip",
        "compare " + a + " " + b + " --peak 0",
        "compare " + a + " " + b + " --threads 2",  // no such option for compare
        "preview " + a + " -o " + png + " --exposure nan",
        "preview " + a + " -o " + png + " --false-colour --channels R --range 0,nan",
        "plan " + a + " -o " + out + " --mu 0",
        "plan " + a + " -o " + out + " --alpha 2",
        "plan " + a + " -o " + out + " --first-pass 0",
        "plan " + a + " -o " + out + " --first-pass 50 --max-spp 10",
        "plan " + a + " -o " + out + " --map nosuchrole=X",
        "plan " + a + " -o " + out + " --threads -1",
    };
    for (const std::string &command : commands) {
        INFO(command);
        const auto result = run_aaf(command);
        CHECK(result.exit_code == 2);
        CHECK(one_error_line(result.output));
    }
    CHECK(names_in(dir) == before);
}

TEST_CASE("the option parser's own errors are one aaf: error line and exit 2, help exits 0",
          "[cli][reliability]") {
    const fs::path dir = scratch_dir("reliability_parse_errors");
    write_flat(dir / "a.exr", 0.5f);
    const std::string a = (dir / "a.exr").string();
    for (const std::string &args :
         {std::string("frobnicate"), "info " + a + " --bogus", "filter aaf " + a + " -o",
          "filter aaf " + a + " -o x.exr --threads abc", std::string("info")}) {
        INFO(args);
        const auto result = run_aaf(args);
        CHECK(result.exit_code == 2);
        CHECK(one_error_line(result.output));
    }
    const auto help = run_aaf("compare --help");
    CHECK(help.exit_code == 0);
    CHECK_THAT(help.output, Catch::Contains("--crop") && !Catch::Contains("aaf: error"));
    CHECK(run_aaf("--version").exit_code == 0);
}

TEST_CASE("preview with a missing channel names the input, not the output", "[cli][reliability]") {
    const fs::path dir = scratch_dir("reliability_preview_channel");
    write_flat(dir / "a.exr", 0.5f);
    const std::string a = (dir / "a.exr").string(), png = (dir / "shown.png").string();
    const std::vector<std::string> before = names_in(dir);
    for (const char *options : {"--channels Z", "--channels R,G,Q", "--false-colour --channels Z"}) {
        INFO(options);
        const auto result = run_aaf("preview " + a + " -o " + png + " " + options);
        CHECK(result.exit_code == 3);
        CHECK(one_error_line(result.output));
        CHECK_THAT(result.output,
                   Catch::StartsWith("aaf: error: " + a + ": ") && !Catch::Contains("shown.png"));
    }
    CHECK(names_in(dir) == before);
}

TEST_CASE("preview and heatmap refuse a PNG output not named .png: one usage line, nothing written",
          "[cli][reliability]") {
    const fs::path dir = scratch_dir("reliability_png_names");
    write_flat(dir / "a.exr", 0.5f);
    write_flat(dir / "b.exr", 0.25f);
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    const std::vector<std::string> before = names_in(dir);
    for (const std::string &command :
         {"preview " + a + " -o " + (dir / "shown.exr").string(),
          "preview " + a + " -o " + (dir / "shown.EXR").string(),
          "compare " + a + " " + b + " --heatmap " + (dir / "hm.EXR").string()}) {
        INFO(command);
        const auto result = run_aaf(command);
        CHECK(result.exit_code == 2);
        CHECK(one_error_line(result.output));
        CHECK_THAT(result.output, Catch::Contains(".png") && !Catch::Contains("libpng"));
    }
    CHECK(names_in(dir) == before);
}

TEST_CASE("an error message with line breaks or raw bytes is still one line", "[cli][reliability]") {
    const fs::path dir = scratch_dir("reliability_one_line");
    write_flat(dir / "a.exr", 0.5f);
    const std::string a = (dir / "a.exr").string();
    // A channel name with a newline and a raw control byte, as a hostile file could carry.
    const auto result = run_aaf("preview " + a + " -o " + (dir / "p.png").string() +
                                " --channels \"$(printf 'X\\nY\\001Z')\"");
    CHECK(result.exit_code == 3);
    CHECK(one_error_line(result.output));
    CHECK_THAT(result.output, Catch::Contains("X; Y\\x01Z"));
}

TEST_CASE("The memory budget flag --memory-limit-gb lowers and raises the image budget of any command",
          "[cli][reliability]") {
    const fs::path dir = scratch_dir("memory_limit_flag");
    const std::string image = (dir / "small.exr").string();
    REQUIRE(run_aaf("render grids -o " + image + " --width 64 --height 48 --spp 1").exit_code == 0);
    // 64 x 48 x about 19 float channels is about 0.2 MB: over 0.0001 GiB (107 KB).
    const aaf_test::RunResult low = run_aaf("info " + image + " --memory-limit-gb 0.0001");
    CHECK(low.exit_code == 3);
    CHECK_THAT(low.output, Catch::Contains(image) && Catch::Contains("memory limit") &&
                               Catch::Contains("--memory-limit-gb"));
    CHECK(run_aaf("--memory-limit-gb 1 info " + image).exit_code == 0);
    CHECK(run_aaf("info " + image + " --memory-limit-gb 0").exit_code == 2);
}

TEST_CASE("More threads than cores run without a oneTBB warning, more than 1024 is a usage error",
          "[cli][reliability]") {
    const fs::path dir = scratch_dir("many_threads");
    const std::string noisy = (dir / "noisy.exr").string(), out = (dir / "out.exr").string();
    REQUIRE(run_aaf("render grids -o " + noisy + " --width 32 --height 24 --spp 2").exit_code == 0);
    const aaf_test::RunResult many = run_aaf("filter aaf " + noisy + " -o " + out + " --threads 64");
    CHECK(many.exit_code == 0);
    CHECK_THAT(many.output, !Catch::Contains("TBB"));
    const aaf_test::RunResult too_many = run_aaf("filter aaf " + noisy + " -o " + out + " --threads 99999");
    CHECK(too_many.exit_code == 2);
    CHECK(std::count(too_many.output.begin(), too_many.output.end(), '\n') == 1);
}
