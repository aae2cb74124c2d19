// `aaf render --aovs` as the group and method registries declare it, and
// the seeds of a sequence's frames.
#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

const std::string kTiny = " --width 32 --height 24 --spp 2 --progress none";

/// What `aaf info` says of method `name` ("ready", "missing 2", ...), or "" when it names none.
std::string info_status(const std::string &info, const std::string &name) {
    std::istringstream lines(info);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t start = line.find_first_not_of(' ');
        if (start == std::string::npos || line.compare(start, name.size() + 1, name + " ") != 0) continue;
        const std::size_t status = line.find_first_not_of(' ', start + name.size());
        return status == std::string::npos ? "" : line.substr(status);
    }
    return "";
}

/// The --aovs entry of `aaf render --help`: from the option to the next one.
std::string aovs_help() {
    const std::string help = run_aaf("render --help").output;
    const std::size_t begin = help.find("--aovs");
    REQUIRE(begin != std::string::npos);
    return help.substr(begin, help.find("\n  -", begin) - begin);
}

/// Whether `text` has `word` with no name character ([a-z0-9_-]) on either side.
bool has_word(const std::string &text, const std::string &word) {
    auto name_char = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    };
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
        if ((at == 0 || !name_char(text[at - 1])) &&
            (at + word.size() == text.size() || !name_char(text[at + word.size()])))
            return true;
    return false;
}

std::vector<float> plane(const aaf::AovSet &aovs, const std::string &name) {
    const aaf::ConstPlaneView view = aovs.channel(name);
    return std::vector<float>(view.data, view.data + aovs.pixel_count());
}

bool same_channels(const aaf::AovSet &a, const aaf::AovSet &b) {
    if (a.channel_names() != b.channel_names()) return false;
    for (const std::string &name : a.channel_names())
        if (plane(a, name) != plane(b, name)) return false;
    return true;
}

}  // namespace

TEST_CASE("CLI: after render --aovs all, aaf info lists every registered method as ready",
          "[cli][render][aovs]") {
    const fs::path dir = scratch_dir("render_aovs_all");
    const std::string out = (dir / "all.exr").string();
    REQUIRE(run_aaf("render grids --aovs all" + kTiny + " -o " + out).exit_code == 0);
    const auto info = run_aaf("info " + out);
    REQUIRE(info.exit_code == 0);
    for (const aaf::Method *method : aaf::methods()) {
        INFO(method->info().name << " in\n" << info.output);
        CHECK(info_status(info.output, method->info().name).rfind("ready", 0) == 0);
    }
    // Every group is there, maaf6's too, which replaces the beauty: the header and info say so.
    const aaf::AovSet aovs = aaf::io::read_aovs(out);
    CHECK(aovs.attributes.at(aaf::attr::kBeautyEffects) ==
          aaf::AttributeValue(std::string("key_light,soft_shadows,indirect")));
    CHECK_THAT(info.output, Catch::Contains("R,G,B holds \"key_light,soft_shadows,indirect\""));
}

TEST_CASE("CLI: after render --aovs METHOD, aaf info lists that method as ready, for every method",
          "[cli][render][aovs]") {
    const fs::path dir = scratch_dir("render_aovs_method");
    for (const aaf::Method *method : aaf::methods()) {
        const std::string &name = method->info().name;
        const std::string out = (dir / (name + ".exr")).string();
        REQUIRE(run_aaf("render grids --aovs " + name + kTiny + " -o " + out).exit_code == 0);
        const auto info = run_aaf("info " + out);
        INFO(name << " in\n" << info.output);
        CHECK(info_status(info.output, name).rfind("ready", 0) == 0);
    }
}

TEST_CASE("CLI: render --help's --aovs names every registered group and method, and all",
          "[cli][render][aovs]") {
    const std::string help = aovs_help();
    INFO(help);
    for (const aaf::trace::AovGroupInfo &group : aaf::trace::aov_group_table())
        CHECK(has_word(help, group.name));
    for (const aaf::Method *method : aaf::methods()) CHECK(has_word(help, method->info().name));
    CHECK_THAT(help, Catch::Contains("all (every group)"));
}

TEST_CASE(
    "CLI: a static sequence's frames differ in noise, are identical with --fixed-noise, and the header "
    "records the seeds",
    "[cli][render][seed]") {
    const fs::path dir = scratch_dir("render_frame_seeds");
    const std::string render = "render grids --frames 1-2 --seed 3" + kTiny + " -o ";
    REQUIRE(run_aaf(render + (dir / "mixed.####.exr").string()).exit_code == 0);
    REQUIRE(run_aaf(render + (dir / "fixed.####.exr").string() + " --fixed-noise").exit_code == 0);
    const aaf::AovSet mixed[2] = {aaf::io::read_aovs((dir / "mixed.0001.exr").string()),
                                  aaf::io::read_aovs((dir / "mixed.0002.exr").string())};
    const aaf::AovSet fixed[2] = {aaf::io::read_aovs((dir / "fixed.0001.exr").string()),
                                  aaf::io::read_aovs((dir / "fixed.0002.exr").string())};
    // The scene stands still: only the noise can tell the frames apart.
    CHECK(plane(mixed[0], "P.X") == plane(mixed[1], "P.X"));
    CHECK(plane(mixed[0], "shadow.V") != plane(mixed[1], "shadow.V"));
    CHECK(plane(mixed[0], "R") != plane(mixed[1], "R"));
    CHECK(same_channels(fixed[0], fixed[1]));
    for (int f = 0; f < 2; ++f) {
        INFO("frame " << f + 1);
        CHECK(mixed[f].attributes.at(aaf::attr::kSeed) ==
              aaf::AttributeValue(int(aaf::trace::frame_seed(3, double(f + 1)))));
        CHECK(mixed[f].attributes.at(aaf::attr::kBaseSeed) == aaf::AttributeValue(3));
        CHECK(fixed[f].attributes.at(aaf::attr::kSeed) == aaf::AttributeValue(3));
        CHECK(fixed[f].attributes.count(aaf::attr::kBaseSeed) == 0);
    }
    // A single render draws with --seed itself, as before.
    const std::string single = (dir / "single.exr").string();
    REQUIRE(run_aaf("render grids --seed 3" + kTiny + " -o " + single).exit_code == 0);
    const aaf::AovSet one = aaf::io::read_aovs(single);
    CHECK(one.attributes.at(aaf::attr::kSeed) == aaf::AttributeValue(3));
    CHECK(one.attributes.count(aaf::attr::kBaseSeed) == 0);
    CHECK(same_channels(one, fixed[0]));
}
