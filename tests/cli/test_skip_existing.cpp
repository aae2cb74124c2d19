// Provenance in every output and --skip-existing that skips only complete,
// up-to-date outputs: a checkpoint, a changed parameter, a newer input and a
// killed run's leftovers are redone.
#include <catch2/catch.hpp>

#include <chrono>
#include <fstream>
#include <iterator>

#include "aaf/io/exr_io.h"
#include "run_aaf.h"

using aaf_test::run_aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

/// The status of the one frame of a `--progress jsonl` run ("ok", "skipped", ...).
std::string frame_status(const aaf_test::RunResult &result) {
    const std::string key = "\"status\":\"";
    const std::size_t at = result.output.find(key);
    if (at == std::string::npos) return "none: " + result.output;
    const std::size_t from = at + key.size();
    return result.output.substr(from, result.output.find('"', from) - from);
}

std::string string_attribute(const aaf::AovSet &aovs, const std::string &name) {
    auto it = aovs.attributes.find(name);
    return it == aovs.attributes.end() ? "" : std::get<std::string>(it->second);
}

/// What a killed run leaves: the output cut in half (a copy interrupted, a
/// writer that was not atomic) and a writer's temporary beside it.
void leave_killed_run(const std::string &path) {
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
    std::ofstream(path + ".tmp-killed", std::ios::binary) << bytes.substr(0, bytes.size() / 3);
}

/// Moves a file's modification time 10 s later, as saving it again would.
void touch_later(const fs::path &path) {
    fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(10));
}

}  // namespace

TEST_CASE("render --skip-existing redoes a checkpoint, a changed parameter, a newer scene and a killed run",
          "[cli][skip-existing]") {
    const fs::path dir = scratch_dir("skip_existing_render");
    const fs::path scene = dir / "grids.json";
    fs::copy_file(fs::path(AAF_SCENE_DIR) / "grids.json", scene);
    const std::string out = (dir / "out.exr").string();
    const auto render = [&](const std::string &spp) {
        return run_aaf("render " + scene.string() + " --width 16 --height 12 --spp " + spp +
                       " --progress jsonl --skip-existing -o " + out);
    };
    CHECK(frame_status(render("4")) == "ok");
    CHECK(frame_status(render("4")) == "skipped");  // up to date

    // The output records how it was made.
    aaf::AovSet made = aaf::io::read_aovs(out);
    CHECK(string_attribute(made, "Software") == "aaf 0.1.0");
    CHECK(string_attribute(made, "aaf:provenance:method") == "render");
    CHECK_THAT(string_attribute(made, "aaf:provenance:parameters"), Catch::Contains("spp=4 seed=1"));
    CHECK(string_attribute(made, "aaf:provenance:command") ==
          "aaf render " + scene.string() + " --width 16 --height 12 --spp 4");
    CHECK(string_attribute(made, "aaf:provenance:inputs_hash").size() == 16);

    // A checkpoint (fewer samples done than asked for) is never done.
    made.attributes["aaf:spp_done"] = 2;
    aaf::io::write_aovs(made, out);
    CHECK(frame_status(render("4")) == "ok");
    CHECK(std::get<int>(aaf::io::read_aovs(out).attributes.at("aaf:spp_done")) == 4);

    CHECK(frame_status(render("8")) == "ok");  // a changed parameter
    CHECK(frame_status(render("8")) == "skipped");
    touch_later(scene);  // a newer input
    CHECK(frame_status(render("8")) == "ok");
    CHECK(frame_status(render("8")) == "skipped");
    leave_killed_run(out);
    CHECK(frame_status(render("8")) == "ok");
    CHECK(aaf::io::is_readable_image(out));
}

TEST_CASE("filter --skip-existing redoes a changed parameter, a newer input and a killed run",
          "[cli][skip-existing]") {
    const fs::path dir = scratch_dir("skip_existing_filter");
    const std::string in = (dir / "in.exr").string(), out = (dir / "out.exr").string();
    REQUIRE(run_aaf("render grids --width 16 --height 12 --spp 4 -o " + in).exit_code == 0);
    const auto filter = [&](const std::string &options) {
        return run_aaf("filter aaf " + in + " -o " + out + " --progress jsonl --skip-existing" + options);
    };
    CHECK(frame_status(filter("")) == "ok");
    CHECK(frame_status(filter("")) == "skipped");

    const aaf::AovSet made = aaf::io::read_aovs(out);
    CHECK(string_attribute(made, "Software") == "aaf 0.1.0");  // not the input's
    CHECK(string_attribute(made, "aaf:provenance:method") == "aaf");
    CHECK_THAT(string_attribute(made, "aaf:provenance:parameters"),
               Catch::Contains("filter=separable") && Catch::Contains("borders=symmetric"));
    CHECK(string_attribute(made, "aaf:provenance:command") == "aaf filter aaf " + in);

    CHECK(frame_status(filter(" --filter 2d")) == "ok");  // a changed parameter
    CHECK(frame_status(filter(" --filter 2d")) == "skipped");
    CHECK(frame_status(filter(" --filter 2d --keep-beauty")) == "ok");  // a changed output option
    touch_later(in);
    CHECK(frame_status(filter(" --filter 2d --keep-beauty")) == "ok");
    leave_killed_run(out);
    CHECK(frame_status(filter(" --filter 2d --keep-beauty")) == "ok");
    CHECK(frame_status(filter(" --filter 2d --keep-beauty")) == "skipped");
}

TEST_CASE("render --progress lines reports while a single round renders, with an ETA", "[cli][progress]") {
    const fs::path dir = scratch_dir("render_progress_lines");
    const auto result = run_aaf("render grids --width 64 --height 48 --spp 64 --progress lines -o " +
                                (dir / "p.exr").string());
    REQUIRE(result.exit_code == 0);
    std::size_t lines = 0;
    for (std::size_t at = result.output.find("render: "); at != std::string::npos;
         at = result.output.find("render: ", at + 1))
        ++lines;
    CHECK(lines >= 3);  // 12 tiles in one round of 64 spp: a line per 10 %
    CHECK_THAT(result.output, Catch::Contains("64/64 spp (100%)") && Catch::Contains("ETA"));
}
