// `render --adaptive` and `aaf plan` take the parameters the plan shares
// with the filter from AAF's own declarations: one spelling, one range, one
// default, and the render's provenance names them as AAF does.
#include <catch2/catch.hpp>

#include <cctype>
#include <filesystem>
#include <string>
#include <variant>

#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/io/exr_io.h"
#include "flat_image.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;

namespace {

/// The help text of option `option` in `help`, from its name to the next
/// option, its line breaks and runs of spaces as one space.
std::string option_help(const std::string &help, const std::string &option) {
    const std::size_t at = help.find("  " + option + " ");
    if (at == std::string::npos) return "";
    const std::size_t next = help.find("\n  --", at + 1);
    std::string text;
    for (char c : help.substr(at + 2, next == std::string::npos ? std::string::npos : next - at - 2))
        if (!std::isspace(static_cast<unsigned char>(c)))
            text += c;
        else if (!text.empty() && text.back() != ' ')
            text += ' ';
    return text;
}

}  // namespace

TEST_CASE(
    "CLI: render --adaptive and plan take mu, light_bandlimit, light_axes and pixel_footprint from "
    "AAF's declarations: one spelling, range and default",
    "[cli][parameters]") {
    const auto filter = run_aaf("filter aaf --help"), plan = run_aaf("plan --help"),
               render = run_aaf("render --help");
    REQUIRE(filter.exit_code == 0);
    REQUIRE(plan.exit_code == 0);
    REQUIRE(render.exit_code == 0);
    for (const std::string &name : aaf::aaf_plan_parameter_names()) {
        const aaf::ParameterInfo &info = aaf::aaf_parameter_declarations().info(name);
        const std::string type = info.type == aaf::ParameterType::Float ? "FLOAT" : "TEXT";
        for (const auto *help : {&filter.output, &plan.output, &render.output}) {
            const std::string text = option_help(*help, info.option_name());
            INFO(name << ": " << text);
            CHECK(text.find(info.option_name() + " " + type + "=" + info.default_value) == 0);
            CHECK(text.find(info.range_text()) != std::string::npos);
        }
    }
    // The same range refuses the same value, named as typed.
    const fs::path dir = aaf_test::scratch_dir("plan_parameters");
    aaf_test::write_flat(dir / "a.exr", 0.5f);
    const std::string out = (dir / "out.exr").string();
    for (const std::string &command :
         {"plan " + (dir / "a.exr").string() + " -o " + out + " --mu 0",
          "render grids -o " + out + " --width 8 --height 8 --spp 1 --progress none --adaptive --mu 0",
          "filter aaf " + (dir / "a.exr").string() + " -o " + out + " --mu 0"}) {
        const auto run = run_aaf(command);
        INFO(command << ": " << run.output);
        CHECK(run.exit_code == 2);
        CHECK(run.output.find("aaf: error: --mu: method 'aaf': parameter 'mu' must be in > 0, got 0") !=
              std::string::npos);
    }
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("CLI: an adaptive render's provenance names the plan's AAF parameters as the filter declares them",
          "[cli][parameters][provenance]") {
    const fs::path dir = aaf_test::scratch_dir("plan_parameters_provenance");
    const std::string out = (dir / "adaptive.exr").string();
    REQUIRE(run_aaf("render grids -o " + out +
                    " --width 16 --height 12 --spp 1 --progress none --adaptive --mu 0.3 --light-bandlimit "
                    "spectrum --light-axes shortest --pixel-footprint projected")
                .exit_code == 0);
    const aaf::AovSet made = aaf::io::read_aovs(out);
    const std::string parameters = std::get<std::string>(made.attributes.at("aaf:provenance:parameters"));
    CHECK_THAT(parameters, Catch::Contains(" adaptive=1 mu=0.3 max_spp=100 light_bandlimit=spectrum "
                                           "light_axes=shortest pixel_footprint=projected "));
    CHECK(std::get<float>(made.attributes.at(aaf::attr::kAdaptiveMu)) == 0.3f);
    // At the defaults, the declared default texts.
    REQUIRE(run_aaf("render grids -o " + out + " --width 16 --height 12 --spp 1 --progress none --adaptive")
                .exit_code == 0);
    const aaf::AovSet plain = aaf::io::read_aovs(out);
    CHECK_THAT(std::get<std::string>(plain.attributes.at("aaf:provenance:parameters")),
               Catch::Contains(" mu=2 max_spp=100 light_bandlimit=sigma light_axes=per_axis "
                               "pixel_footprint=receiver "));
}
