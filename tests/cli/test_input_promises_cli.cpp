// Promises about bad inputs kept through the real `aaf`: channels are never
// borrowed from another pass, header attributes are checked before use, a
// finite input never becomes Inf, and each refusal has its documented exit
// code and one error line naming the file, attribute or option.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/io/exr_io.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

const std::string kSmall = " --width 24 --height 16 --spp 4 --progress none";

/// True when `output` holds exactly one `aaf: error:` line (warnings and notes aside).
bool one_error_line(const std::string &output) {
    int errors = 0, others = 0;
    std::size_t start = 0;
    while (start < output.size()) {
        const std::size_t end = output.find('\n', start);
        const std::string line = output.substr(start, end - start);
        if (line.rfind("aaf: error: ", 0) == 0)
            ++errors;
        else if (!line.empty() && line.rfind("aaf: warning: ", 0) != 0 && line.rfind("aaf: note: ", 0) != 0)
            ++others;
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return errors == 1 && others == 0;
}

/// `source` with header attribute `name` set to `value`, written as `target`.
void with_attribute(const fs::path &source, const fs::path &target, const std::string &name,
                    const aaf::AttributeValue &value) {
    aaf::AovSet aovs = aaf::io::read_aovs(source.string());
    aovs.attributes[name] = value;
    aaf::io::write_aovs(aovs, target.string());
}

/// `source` without channel `name`, written as `target`.
void without_channel(const fs::path &source, const fs::path &target, const std::string &name) {
    aaf::AovSet aovs = aaf::io::read_aovs(source.string());
    aovs.take_channel(name);
    aaf::io::write_aovs(aovs, target.string());
}

}  // namespace

TEST_CASE("CLI: a role is read only from its own name, a --map, or a renderer synonym", "[cli][inputs]") {
    const fs::path dir = scratch_dir("promise_own_names");
    const std::string in = (dir / "s.exr").string(), out = (dir / "o.exr").string();
    // No Z and no R,G,B: depth must not come from P.Z, nor the beauty from unshadowed.R/G/B.
    const std::string rendered_isg = (dir / "isg.exr").string();
    REQUIRE(
        run_aaf("render grids -o " + rendered_isg + " --aovs isg,position,unshadowed" + kSmall).exit_code ==
        0);
    without_channel(rendered_isg, in, "Z");
    const auto isg = run_aaf("filter isg-shadow " + in + " -o " + out);
    CHECK(isg.exit_code == 3);
    CHECK(one_error_line(isg.output));
    CHECK(isg.output.find("depth") != std::string::npos);
    CHECK(isg.output.find(in) != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    // A file without R,G,B: the filtered image must not be written over unshadowed.R/G/B.
    const std::string shadow = (dir / "shadow.exr").string(), no_rgb = (dir / "no_rgb.exr").string();
    REQUIRE(run_aaf("render grids -o " + shadow + " --aovs aaf" + kSmall).exit_code == 0);
    const aaf::AovSet rendered = aaf::io::read_aovs(shadow);
    aaf::AovSet stripped(rendered.width(), rendered.height());
    stripped.attributes = rendered.attributes;
    for (const std::string &name : rendered.channel_names())
        if (name != "R" && name != "G" && name != "B") {
            const aaf::ConstPlaneView from = rendered.channel(name);
            const aaf::PlaneView to = stripped.add_channel(name);
            std::copy(from.data, from.data + rendered.pixel_count(), to.data);
        }
    aaf::io::write_aovs(stripped, no_rgb);
    for (const char *method : {"gaussian", "aaf"}) {
        const auto run = run_aaf(std::string("filter ") + method + " " + no_rgb + " -o " + out);
        INFO(method << ": " << run.output);
        REQUIRE(run.exit_code == 0);
        const aaf::AovSet filtered = aaf::io::read_aovs(out);
        CHECK(filtered.has_channel("R"));
        for (const char *name : {"unshadowed.R", "unshadowed.G", "unshadowed.B"}) {
            const aaf::ConstPlaneView before = stripped.channel(name), after = filtered.channel(name);
            CHECK(std::equal(before.data, before.data + stripped.pixel_count(), after.data));
        }
        fs::remove(out);
    }
    const auto info = run_aaf("info " + in);
    CHECK(info.output.find("isg-shadow  ready") == std::string::npos);
    // Given with --map, the same channel is read.
    CHECK(run_aaf("filter isg-shadow " + in + " -o " + out + " --map depth=P.Z").exit_code == 0);
}

TEST_CASE("CLI: an ISG header attribute out of range is refused, naming it and the file", "[cli][inputs]") {
    const fs::path dir = scratch_dir("promise_isg_headers");
    const fs::path in = dir / "isg.exr";
    REQUIRE(run_aaf("render grids -o " + in.string() + " --aovs isg,all" + kSmall).exit_code == 0);
    struct Bad {
        const char *method, *attribute;
        aaf::AttributeValue value;
    };
    const float nan = std::nanf("");
    const Bad cases[] = {
        {"isg-shadow", aaf::attr::kCameraFocalPx, 0.0f},
        {"isg-shadow", aaf::attr::kCameraFocalPx, -3.0f},
        {"isg-glossy", aaf::attr::kCameraFocalPx, nan},
        {"isg-dof", aaf::attr::kCameraFocalPx, 1e30f},
        {"isg-glossy", aaf::attr::kCameraEye, aaf::Vec3{nan, 1, 1}},
        {"isg-dof", aaf::attr::kApertureRadius, nan},
        {"isg-dof", aaf::attr::kApertureRadius, -0.1f},
        {"isg-dof", aaf::attr::kFocusDistance, 0.0f},
    };
    int index = 0;
    for (const Bad &bad : cases) {
        const fs::path file = dir / ("bad" + std::to_string(index++) + ".exr"), out = dir / "o.exr";
        with_attribute(in, file, bad.attribute, bad.value);
        // The focus distance is read only for a lens: give the render one.
        if (std::string(bad.attribute) == aaf::attr::kFocusDistance)
            with_attribute(file, file, aaf::attr::kApertureRadius, 0.05f);
        const auto run =
            run_aaf(std::string("filter ") + bad.method + " " + file.string() + " -o " + out.string());
        INFO(bad.method << " " << bad.attribute << ": " << run.output);
        CHECK(run.exit_code == 3);
        CHECK(one_error_line(run.output));
        CHECK(run.output.find(bad.attribute) != std::string::npos);
        CHECK(run.output.find(file.string()) != std::string::npos);
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("CLI: a declared light count is checked before it sizes an allocation", "[cli][inputs]") {
    const fs::path dir = scratch_dir("promise_light_count");
    const fs::path in = dir / "ratio.exr", bad = dir / "lights.exr", out = dir / "o.exr";
    REQUIRE(run_aaf("render grids -o " + in.string() + " --aovs ratio" + kSmall).exit_code == 0);
    for (int count : {1000000, 2147483647}) {
        with_attribute(in, bad, aaf::attr::kRatioLights, count);
        // Under a 1 GB address-space limit: the refusal must come before any allocation sized by the count.
        const auto run = run_aaf("filter ratio " + bad.string() + " -o " + out.string(),
                                 "ulimit -v 1000000; " + std::string(AAF_EXECUTABLE));
        INFO(run.output);
        CHECK(run.exit_code == 3);
        CHECK(one_error_line(run.output));
        CHECK(run.output.find("aaf:ratio:lights") != std::string::npos);
        CHECK(run.output.find(bad.string()) != std::string::npos);
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("CLI: a finite input gives a finite output or an error naming the file and channel",
          "[cli][inputs]") {
    const fs::path dir = scratch_dir("promise_finite_output");
    const fs::path in = dir / "ratio.exr", huge = dir / "huge.exr", out = dir / "o.exr";
    REQUIRE(run_aaf("render grids -o " + in.string() + " --aovs ratio,shadow,all" + kSmall).exit_code == 0);
    aaf::AovSet aovs = aaf::io::read_aovs(in.string());
    for (const std::string &name : aovs.channel_names()) {
        if (name.rfind("ratio.", 0) != 0) continue;
        aaf::PlaneView plane = aovs.channel(name);
        std::fill(plane.data, plane.data + aovs.pixel_count(), 3e38f);
    }
    aaf::io::write_aovs(aovs, huge.string());
    // AAF's widths and the control variate U - U_N + S_N: sums of 3e38 overflowed to Inf.
    const auto run = run_aaf("filter ratio " + huge.string() + " -o " + out.string() +
                             " --denoiser aaf --estimator control-variate");
    INFO(run.output);
    if (run.exit_code == 0) {
        const aaf::AovSet filtered = aaf::io::read_aovs(out.string());
        for (const char *name : {"R", "G", "B"})
            for (float v : filtered.plane(filtered.index_of(name))) REQUIRE(std::isfinite(v));
    } else {
        CHECK(run.exit_code == 3);
        CHECK(one_error_line(run.output));
        CHECK(run.output.find(huge.string()) != std::string::npos);
        CHECK(run.output.find("'ratio.") != std::string::npos);
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("CLI: a negative --seed is a usage error on every command that takes one", "[cli][inputs]") {
    const fs::path dir = scratch_dir("promise_seed");
    for (const std::string &command :
         {std::string("analyze wedge --random 2 --grid 16 --seed -1"),
          "render grids -o " + (dir / "s.exr").string() + kSmall + " --seed -1"}) {
        const auto run = run_aaf(command);
        INFO(command << ": " << run.output);
        CHECK(run.exit_code == 2);
        CHECK(one_error_line(run.output));
        CHECK(run.output.find("--seed") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(dir / "s.exr"));
}

TEST_CASE(
    "CLI: analyze wedge computes every slope its --smin and --smax accept, and names the option past them",
    "[cli][inputs]") {
    const auto inside = run_aaf("analyze wedge --smin 1e-100 --smax 1e100 --gauss --grid 16");
    INFO(inside.output);
    CHECK(inside.exit_code == 0);
    const auto outside = run_aaf("analyze wedge --smin 1e-300 --smax 1e300 --gauss --grid 16");
    CHECK(outside.exit_code == 2);
    CHECK(one_error_line(outside.output));
    CHECK(outside.output.find("--smin") != std::string::npos);
}

TEST_CASE("CLI: a parameter a delegate does not take is a usage error, the same from filter and render",
          "[cli][inputs]") {
    const fs::path dir = scratch_dir("promise_delegate_parameter");
    const std::string m6 = (dir / "M6.exr").string(), out = (dir / "o.exr").string();
    const std::string tiny = " --width 16 --height 12 --spp 4 --progress none";
    REQUIRE(run_aaf("render grids -o " + m6 + " --aovs maaf6" + tiny).exit_code == 0);
    const auto filter = run_aaf("filter maaf " + m6 + " -o " + out + " --k 2");
    const auto render =
        run_aaf("render grids -o " + out + " --aovs maaf6 --filter maaf --filter-param k=2" + tiny);
    INFO(filter.output << render.output);
    CHECK(filter.exit_code == 2);
    CHECK(render.exit_code == 2);
    CHECK(one_error_line(filter.output));
    CHECK(one_error_line(render.output));
    // One message: the filter's names its file first.
    const std::string message = render.output.substr(std::string("aaf: error: ").size());
    CHECK(filter.output == "aaf: error: " + m6 + ": " + message);
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("CLI: a render option without effect is named in a warning", "[cli][inputs]") {
    const fs::path dir = scratch_dir("promise_no_effect");
    const std::string out = (dir / "w.exr").string();
    const auto effects = run_aaf("render grids -o " + out + kSmall + " --maaf6-effects shadows");
    CHECK(effects.exit_code == 0);
    CHECK(effects.output.find("aaf: warning: --maaf6-effects has no effect") != std::string::npos);
    for (const char *option :
         {"--light-bandlimit sigma", "--light-axes shortest", "--pixel-footprint receiver"}) {
        const auto run = run_aaf("render grids -o " + out + kSmall + " " + option);
        INFO(option << ": " << run.output);
        CHECK(run.exit_code == 0);
        CHECK(
            run.output.find("aaf: warning: " + std::string(option).substr(0, std::string(option).find(' ')) +
                            " has no effect without --adaptive") != std::string::npos);
    }
    // With the group, no warning.
    const auto with_group = run_aaf("render grids -o " + out +
                                    " --width 16 --height 12 --spp 4 --progress none --aovs maaf6 "
                                    "--maaf6-effects shadows");
    CHECK(with_group.exit_code == 0);
    CHECK(with_group.output.find("warning") == std::string::npos);
}

TEST_CASE("CLI: a --map layer keeps only the component suffix, as for every multi-channel role",
          "[cli][inputs]") {
    const fs::path dir = scratch_dir("promise_map_layer");
    const fs::path in = dir / "ratio.exr", renamed = dir / "renamed.exr", out = dir / "o.exr",
                   reference = dir / "r.exr";
    REQUIRE(run_aaf("render grids -o " + in.string() + " --aovs ratio" + kSmall).exit_code == 0);
    // A renderer's myU.R/G/B for the analytic U.
    aaf::AovSet aovs = aaf::io::read_aovs(in.string());
    aaf::AovSet copy(aovs.width(), aovs.height());
    copy.attributes = aovs.attributes;
    for (const std::string &name : aovs.channel_names()) {
        // The per-light layer too, named as a --map'd channel's is (ratio_layers.h: myU.L0.R).
        const std::string target = name.rfind("ratio.U.", 0) == 0      ? "myU." + name.substr(8)
                                   : name.rfind("ratio.L0.U.", 0) == 0 ? "myU.L0." + name.substr(11)
                                                                       : name;
        aaf::PlaneView plane = copy.add_channel(target);
        const aaf::ConstPlaneView source = static_cast<const aaf::AovSet &>(aovs).channel(name);
        for (int y = 0; y < aovs.height(); ++y)
            for (int x = 0; x < aovs.width(); ++x) plane(x, y) = source(x, y);
    }
    aaf::io::write_aovs(copy, renamed.string());
    REQUIRE(run_aaf("filter ratio " + in.string() + " -o " + reference.string()).exit_code == 0);
    const auto run =
        run_aaf("filter ratio " + renamed.string() + " -o " + out.string() + " --map ratio_u=myU");
    INFO(run.output);
    REQUIRE(run.exit_code == 0);
    CHECK(
        run_aaf("compare " + out.string() + " " + reference.string() + " --channels R,G,B --fail-above mae=0")
            .exit_code == 0);
}
