// `aaf render --filter METHOD`: render, filter and write in one process. The
// output must be what `aaf render` followed by `aaf filter METHOD` writes,
// pixel for pixel, and every bad option must be refused before anything
// renders.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/io/exr_io.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::interrupt_at_first_checkpoint;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

/// Every channel of `a` and `b` (names in order, then values bit for bit).
void require_same_pixels(const fs::path &a_path, const fs::path &b_path) {
    const aaf::AovSet a = aaf::io::read_aovs(a_path.string());
    const aaf::AovSet b = aaf::io::read_aovs(b_path.string());
    REQUIRE(a.channel_names() == b.channel_names());
    REQUIRE(a.width() == b.width());
    REQUIRE(a.height() == b.height());
    for (const std::string &name : a.channel_names()) {
        INFO("channel " << name);
        const float *pa = a.channel(name).data, *pb = b.channel(name).data;
        CHECK(std::vector<float>(pa, pa + a.pixel_count()) == std::vector<float>(pb, pb + b.pixel_count()));
    }
}

std::string string_attribute(const aaf::AovSet &aovs, const std::string &name) {
    auto it = aovs.attributes.find(name);
    return it == aovs.attributes.end() ? "" : std::get<std::string>(it->second);
}

}  // namespace

TEST_CASE("render --filter writes what render then filter write, pixel for pixel", "[cli][render]") {
    const fs::path dir = scratch_dir("render_filter_same");
    const std::string size = " --width 64 --height 48 --progress none";

    SECTION("aaf on an adaptive render, a parameter set") {
        REQUIRE(run_aaf("render grids --adaptive" + size + " -o " + (dir / "aovs.exr").string()).exit_code ==
                0);
        REQUIRE(run_aaf("filter aaf --k 2 --progress none " + (dir / "aovs.exr").string() + " -o " +
                        (dir / "two.exr").string())
                    .exit_code == 0);
        const auto one = run_aaf("render grids --adaptive --filter aaf --filter-param k=2" + size + " -o " +
                                 (dir / "one.exr").string());
        // The option's spelling in `aaf filter aaf --help` names the same parameter.
        REQUIRE(run_aaf("render grids --adaptive --filter aaf --filter-param --k=2" + size + " -o " +
                        (dir / "spelled.exr").string())
                    .exit_code == 0);
        require_same_pixels(dir / "one.exr", dir / "spelled.exr");
        REQUIRE(one.exit_code == 0);
        CHECK_THAT(one.output, Catch::Contains(", filter "));  // the adaptive summary times the filter
        require_same_pixels(dir / "two.exr", dir / "one.exr");
        // The header says how it was made: the render's settings and the filter's.
        const aaf::AovSet made = aaf::io::read_aovs((dir / "one.exr").string());
        const std::string parameters = string_attribute(made, "aaf:provenance:parameters");
        CHECK_THAT(parameters, Catch::Contains("adaptive=1"));
        CHECK_THAT(parameters, Catch::Contains(" filter=aaf "));
        CHECK_THAT(parameters, Catch::Contains(" filter.k=2 "));
        // A different parameter gives a different image.
        REQUIRE(run_aaf("render grids --adaptive --filter aaf" + size + " -o " + (dir / "k3.exr").string())
                    .exit_code == 0);
        const aaf::AovSet k3 = aaf::io::read_aovs((dir / "k3.exr").string());
        const float *a = made.channel("R").data, *b = k3.channel("R").data;
        CHECK(std::vector<float>(a, a + made.pixel_count()) != std::vector<float>(b, b + k3.pixel_count()));
    }

    SECTION("--keep-beauty, --half and --compression as aaf filter's") {
        const std::string output = " --keep-beauty --half --compression zips";
        REQUIRE(run_aaf("render grids --spp 4" + size + " -o " + (dir / "aovs.exr").string()).exit_code == 0);
        REQUIRE(run_aaf("filter aaf --progress none" + output + " " + (dir / "aovs.exr").string() + " -o " +
                        (dir / "two.exr").string())
                    .exit_code == 0);
        REQUIRE(
            run_aaf("render grids --spp 4 --filter aaf" + output + size + " -o " + (dir / "one.exr").string())
                .exit_code == 0);
        require_same_pixels(dir / "two.exr", dir / "one.exr");
        const aaf::AovSet made = aaf::io::read_aovs((dir / "one.exr").string());
        CHECK(made.has_channel("aaf.R"));  // the filtered image beside the render's own R,G,B
        CHECK(made.precision(made.index_of("R")) == aaf::Precision::Half);
        CHECK(made.precision(made.index_of("P.X")) == aaf::Precision::Float);
        CHECK_THAT(string_attribute(made, "aaf:provenance:parameters"),
                   Catch::Contains("keep_beauty=true half=true compression=zips"));
    }

    SECTION("a sequence through a method that reads the previous frame's output (ratio --temporal)") {
        const std::string frames = " --frames 1-3 --spp 4 --aovs ratio,motion";
        REQUIRE(run_aaf("render grids" + frames + size + " -o " + (dir / "r.####.exr").string()).exit_code ==
                0);
        REQUIRE(run_aaf("filter ratio --temporal --frames 1-3 --progress none " +
                        (dir / "r.####.exr").string() + " -o " + (dir / "rf.####.exr").string())
                    .exit_code == 0);
        REQUIRE(run_aaf("render grids --filter ratio --filter-param temporal=true" + frames + size + " -o " +
                        (dir / "one.####.exr").string())
                    .exit_code == 0);
        for (const char *frame : {"0001", "0002", "0003"}) {
            INFO("frame " << frame);
            require_same_pixels(dir / ("rf." + std::string(frame) + ".exr"),
                                dir / ("one." + std::string(frame) + ".exr"));
        }
    }
}

TEST_CASE("render --filter refuses bad options before it renders", "[cli][render]") {
    const fs::path dir = scratch_dir("render_filter_bad");
    const fs::path out = dir / "out.exr";
    struct Case {
        const char *options, *message;
    };
    for (const Case &c : {
             Case{"--filter nope", "unknown method 'nope'"},
             Case{"--filter aaf --filter-param k", "expected NAME=VALUE"},
             Case{"--filter aaf --filter-param =3", "expected NAME=VALUE"},
             Case{"--filter aaf --filter-param k=-1", "--filter-param 'k=-1'"},
             Case{"--filter aaf --filter-param no_such=1", "--filter-param 'no_such=1'"},
             Case{"--filter aaf --filter-param normal-threshold=200",
                  "--filter-param 'normal-threshold=200'"},
             Case{"--filter-param k=2", "--filter-param needs --filter"},
             Case{"--keep-beauty", "--keep-beauty needs --filter"},
             Case{"--filter aaf --compression zap", "unknown compression 'zap'"},
             Case{"--filter aaf --aovs shadow", "--filter aaf reads AOVs that --aovs shadow does not render"},
         }) {
        INFO(c.options);
        const auto result = run_aaf("render grids --width 16 --height 12 --spp 1 " + std::string(c.options) +
                                    " -o " + out.string());
        CHECK(result.exit_code == 2);
        CHECK_THAT(result.output, Catch::Contains(c.message));
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("render --filter --skip-existing redoes a frame whose filter parameters changed",
          "[cli][render][skip-existing]") {
    const fs::path dir = scratch_dir("render_filter_skip");
    const auto render = [&](const std::string &options) {
        return run_aaf("render grids --width 16 --height 12 --spp 2 --progress jsonl --skip-existing -o " +
                       (dir / "out.exr").string() + options);
    };
    const auto skipped = [](const aaf_test::RunResult &r) {
        return r.output.find("\"status\":\"skipped\"") != std::string::npos;
    };
    REQUIRE(render(" --filter aaf").exit_code == 0);
    CHECK(skipped(render(" --filter aaf")));
    CHECK_FALSE(skipped(render(" --filter aaf --filter-param k=2")));  // a filter parameter changed
    CHECK(skipped(render(" --filter aaf --filter-param k=2")));
    CHECK_FALSE(skipped(render("")));  // unfiltered is another output
}

TEST_CASE("render --filter stopped by Ctrl-C writes the render unfiltered, and --resume --filter finishes it",
          "[cli][render][resume][interrupt]") {
    const fs::path dir = scratch_dir("render_filter_interrupt");
    const std::string out = (dir / "ref.exr").string(), whole = (dir / "whole.exr").string();
    const std::string render = "render grids --width 48 --height 36 --spp 16384 --filter gaussian ";
    CHECK(interrupt_at_first_checkpoint(render + "--checkpoint 0.001 --threads 1 -o " + out, out, dir) ==
          130);
    const aaf::AovSet partial = aaf::io::read_aovs(out);
    CHECK(std::get<int>(partial.attributes.at(aaf::attr::kSppDone)) < 16384);
    // Unfiltered: no filter output beside the render's own channels.
    CHECK_FALSE(partial.has_channel("noisy.R"));
    CHECK_FALSE(partial.has_channel("aaf.V"));

    REQUIRE(run_aaf(render + "--resume " + out + " -o " + out).exit_code == 0);
    REQUIRE(run_aaf(render + "-o " + whole).exit_code == 0);
    const aaf::AovSet finished = aaf::io::read_aovs(out);
    CHECK(finished.has_channel("noisy.R"));
    require_same_pixels(whole, out);
}

TEST_CASE(
    "CLI: render --filter refuses, before it renders, filter parameters that need AOVs --aovs does not "
    "render or do not go together",
    "[cli][render]") {
    const fs::path dir = scratch_dir("render_filter_parameter_groups");
    const std::string render = "render grids --width 16 --height 12 --spp 1 --progress none ";
    struct Case {
        const char *options, *message;
    };
    for (const Case &c : {
             Case{"--frames 1-3 --aovs ratio --filter ratio --filter-param temporal=true",
                  "--filter-param temporal=true: --filter ratio then reads the motion AOVs, which --aovs "
                  "ratio "
                  "does not render (add them: --aovs ratio,motion"},
             Case{"--frames 1-2 --aovs ratio --filter ratio --filter-param denoiser=aaf",
                  "--filter-param denoiser=aaf: --filter ratio then reads the shadow,id AOVs"},
             Case{"--aovs ratio,motion --filter ratio --filter-param grey=true --filter-param "
                  "estimator=stochastic",
                  "--filter-param: ratio: --grey applies to --estimator ratio only"},
             Case{"--filter aaf --filter-param mu_from_spp=true --filter-param fixed_mu=true",
                  "--filter-param: AAF mu from spp and fixed mu exclude each other"},
         }) {
        INFO(c.options);
        const bool sequence = std::string(c.options).find("--frames") != std::string::npos;
        const fs::path out = dir / (sequence ? "out.####.exr" : "out.exr");
        const auto result = run_aaf(render + c.options + " -o " + out.string());
        CHECK(result.exit_code == 2);
        CHECK_THAT(result.output, Catch::Contains(c.message));
        CHECK(fs::is_empty(dir));  // nothing rendered, nothing written
    }
    // `aaf filter` refuses the same combination before it reads its input.
    const auto filter = run_aaf("filter aaf --mu-from-spp --fixed-mu " + (dir / "missing.exr").string() +
                                " -o " + (dir / "out.exr").string());
    CHECK(filter.exit_code == 2);
    CHECK_THAT(filter.output, Catch::Contains("AAF mu from spp and fixed mu exclude each other"));

    // Without --aovs the render writes what the parameters need: a temporal sequence renders motion.
    REQUIRE(run_aaf(render + "--frames 1-2 --filter ratio --filter-param temporal=true -o " +
                    (dir / "rt.####.exr").string())
                .exit_code == 0);
    CHECK(aaf::io::read_aovs((dir / "rt.0002.exr").string()).has_channel("motion.X"));
}
