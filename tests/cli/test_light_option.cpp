// `--light FILE.json` for renderers that write no aaf:light:* header, and the
// list of every missing input with its recipe (aaf info, aaf filter).
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/io/exr_io.h"
#include "run_aaf.h"

using aaf_test::run_aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

/// `full` less the channels `drop` and every aaf:light:* attribute.
aaf::AovSet without(const aaf::AovSet &full, const std::vector<std::string> &drop) {
    aaf::AovSet out(full.width(), full.height());
    out.attributes = full.attributes;
    for (const std::string &name : aaf::light_attribute_names()) out.attributes.erase(name);
    for (std::size_t c = 0; c < full.channel_names().size(); ++c)
        if (std::find(drop.begin(), drop.end(), full.channel_names()[c]) == drop.end())
            std::copy(full.plane(c).begin(), full.plane(c).end(),
                      out.add_channel(full.channel_names()[c]).data);
    return out;
}

float max_difference(const aaf::AovSet &a, const aaf::AovSet &b, const std::string &channel) {
    const aaf::ConstPlaneView pa = a.channel(channel), pb = b.channel(channel);
    float worst = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) worst = std::max(worst, std::abs(pa(x, y) - pb(x, y)));
    return worst;
}

}  // namespace

TEST_CASE("aaf info and filter list every missing input at once, each with its recipe", "[cli][light]") {
    const fs::path dir = scratch_dir("light_missing");
    const std::string full = (dir / "full.exr").string(), bare = (dir / "bare.exr").string();
    REQUIRE(run_aaf("render grids -o " + full + " --width 24 --height 16 --spp 4").exit_code == 0);
    aaf::io::write_aovs(without(aaf::io::read_aovs(full), {"shadow.V", "shadow.d1"}), bare);

    const auto info = run_aaf("info " + bare);
    REQUIRE(info.exit_code == 0);
    const std::string aaf_line = info.output.substr(info.output.find("\n  aaf "));
    CHECK_THAT(aaf_line, Catch::StartsWith("\n  aaf      missing 3"));  // not "ready" without a light
    CHECK_THAT(info.output, Catch::Contains("visibility [shadow.V]: aaf render SCENE --aovs shadow"));
    CHECK_THAT(info.output, Catch::Contains("d1 [shadow.d1]: aaf render SCENE --aovs shadow"));
    CHECK_THAT(info.output, Catch::Contains("--map visibility=CHANNEL"));
    CHECK_THAT(info.output, Catch::Contains("header aaf:light:center,aaf:light:normal"));

    const std::string out = (dir / "out.exr").string();
    const auto filter = run_aaf("filter aaf " + bare + " -o " + out);
    CHECK(filter.exit_code == 3);
    CHECK_THAT(filter.output, Catch::Contains("missing 3 inputs of AAF: visibility [shadow.V]") &&
                                  Catch::Contains("; d1 [shadow.d1]") &&
                                  Catch::Contains("--light LIGHT.json"));
    CHECK(std::count(filter.output.begin(), filter.output.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("A file without a light header filters with --light as with the header it was rendered with",
          "[cli][light]") {
    const fs::path dir = scratch_dir("light_option");
    const std::string full = (dir / "full.exr").string(), bare = (dir / "bare.exr").string();
    REQUIRE(run_aaf("render grids -o " + full + " --width 24 --height 16 --spp 4").exit_code == 0);
    aaf::io::write_aovs(without(aaf::io::read_aovs(full), {}), bare);
    // grids' key light as a light object (SCENE_FORMAT.md), and the scene file itself.
    const std::string light = (dir / "light.json").string();
    std::ofstream(light) << R"({"center": [0, 3.0, 0], "edge_u": [1.0, 0, 0], "edge_v": [0, 0, 1.0]})";
    const std::string scene = std::string(AAF_SCENE_DIR) + "/grids.json";

    CHECK_THAT(run_aaf("info " + bare + " --light " + light).output, Catch::Contains("\n  aaf      ready"));
    const std::string reference = (dir / "reference.exr").string();
    REQUIRE(run_aaf("filter aaf " + full + " -o " + reference).exit_code == 0);
    for (const std::string &given : {light, scene}) {
        INFO(given);
        const std::string out = (dir / "lit.exr").string();
        REQUIRE(run_aaf("filter aaf " + bare + " -o " + out + " --light " + given).exit_code == 0);
        const aaf::AovSet lit = aaf::io::read_aovs(out), ref = aaf::io::read_aovs(reference);
        for (const char *channel : {"R", "G", "B", "aaf.V", "aaf_beta.X"})
            CHECK(max_difference(lit, ref, channel) == 0);
        CHECK(std::get<float>(lit.attributes.at("aaf:light:width_m")) == 1.0f);
    }

    // Precedence: --light replaces the file's own header (a 2 m light blurs more).
    const std::string wide = (dir / "wide.json").string(), out = (dir / "wide.exr").string();
    std::ofstream(wide) << R"({"center": [0, 3.0, 0], "edge_u": [2.0, 0, 0], "edge_v": [0, 0, 2.0]})";
    REQUIRE(run_aaf("filter aaf " + full + " -o " + out + " --light " + wide).exit_code == 0);
    const aaf::AovSet widened = aaf::io::read_aovs(out);
    CHECK(std::get<float>(widened.attributes.at("aaf:light:width_m")) == 2.0f);
    CHECK(max_difference(widened, aaf::io::read_aovs(reference), "aaf.V") > 0);

    // A bad light file is an input error naming it and the field.
    std::ofstream(wide) << R"({"center": [0, 3.0, 0], "edge_u": [2.0, 0, 0]})";
    const auto bad = run_aaf("filter aaf " + full + " -o " + out + " --light " + wide);
    CHECK(bad.exit_code == 3);
    CHECK_THAT(bad.output, Catch::Contains("wide.json: missing required field 'edge_v'"));
}
