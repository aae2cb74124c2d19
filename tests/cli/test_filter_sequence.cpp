#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

/// Renders frames 1-4 of a tiny grids sequence `in.####.exr` into `dir`.
void render_sequence(const fs::path &dir) {
    aaf::trace::RenderSettings settings;
    settings.width = 32;
    settings.height = 24;
    settings.spp = 4;
    for (int frame = 1; frame <= 4; ++frame) {
        settings.seed = std::uint64_t(frame);
        aaf::io::write_aovs(aaf::trace::render_scene("grids", settings),
                            (dir / ("in.000" + std::to_string(frame) + ".exr")).string());
    }
}

std::vector<int> outputs_present(const fs::path &dir) {
    std::vector<int> frames;
    for (int frame = 1; frame <= 4; ++frame)
        if (fs::exists(dir / ("out.000" + std::to_string(frame) + ".exr"))) frames.push_back(frame);
    return frames;
}

bool has_temporaries(const fs::path &dir) {
    for (const auto &entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("filter: a 4-frame sequence with each frame-range syntax", "[cli][sequence]") {
    const fs::path dir = scratch_dir("filter_sequence");
    render_sequence(dir);
    const std::string in = (dir / "in.####.exr").string(), out = (dir / "out.####.exr").string();
    const std::vector<std::pair<std::string, std::vector<int>>> cases = {
        {"--frames 1-4", {1, 2, 3, 4}}, {"--frames 1-4x2", {1, 3}}, {"--frames 1-4:3", {1, 4}},
        {"--frames 2,4", {2, 4}},       {"", {1, 2, 3, 4}},  // all frames found on disk
    };
    for (const auto &[frames, expected] : cases) {
        for (int frame = 1; frame <= 4; ++frame)
            fs::remove(dir / ("out.000" + std::to_string(frame) + ".exr"));
        INFO(frames);
        REQUIRE(run_aaf("filter aaf " + in + " -o " + out + " " + frames).exit_code == 0);
        CHECK(outputs_present(dir) == expected);
    }
    CHECK(aaf::io::read_aovs((dir / "out.0002.exr").string()).has_channel("aaf.V"));

    // A plain output for a sequence would receive every frame: refused, nothing written.
    const auto refused = run_aaf("filter aaf " + in + " -o " + (dir / "all.exr").string());
    CHECK(refused.exit_code == 1);
    CHECK_THAT(refused.output, Catch::Contains("all.exr"));
    CHECK(!fs::exists(dir / "all.exr"));
}

TEST_CASE("filter: a failed frame, then a rerun with --skip-existing completes the job", "[cli][sequence]") {
    const fs::path dir = scratch_dir("filter_resume");
    render_sequence(dir);
    const fs::path good_frame_3 = dir / "in.0003.exr.good";
    fs::copy_file(dir / "in.0003.exr", good_frame_3);
    std::ofstream(dir / "in.0003.exr", std::ios::trunc) << "truncated";  // a broken input frame

    const std::string in = (dir / "in.####.exr").string(), out = (dir / "out.####.exr").string();
    const auto first = run_aaf("filter aaf " + in + " -o " + out + " --frames 1-4 --skip-bad-frames");
    CHECK(first.exit_code == 1);  // the failure still shows in the exit code
    CHECK_THAT(first.output, Catch::Contains("in.0003.exr") && Catch::Contains("1 of 4 frames failed"));
    CHECK(outputs_present(dir) == std::vector<int>{1, 2, 4});
    CHECK(!has_temporaries(dir));

    fs::remove(dir / "in.0003.exr");
    fs::rename(good_frame_3, dir / "in.0003.exr");
    const auto rerun =
        run_aaf("filter aaf " + in + " -o " + out + " --frames 1-4 --skip-existing --progress=jsonl");
    REQUIRE(rerun.exit_code == 0);
    CHECK(outputs_present(dir) == std::vector<int>{1, 2, 3, 4});
    CHECK(!has_temporaries(dir));
    int skipped = 0, ok = 0;
    std::istringstream lines(rerun.output);
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json event = nlohmann::json::parse(line);
        if (event["event"] == "frame_end") (event["status"] == "skipped" ? skipped : ok)++;
        if (event["event"] == "summary") CHECK(event["failed"] == 0);
    }
    CHECK(skipped == 3);
    CHECK(ok == 1);
}

TEST_CASE("filter: peak memory does not grow with the number of frames", "[cli][sequence][memory]") {
    // Frames stream one at a time: 40 frames must peak like 4. Each 320x240
    // frame holds ~6 MB in and out, so keeping them would add ~240 MB.
    const fs::path dir = scratch_dir("filter_memory");
    aaf::trace::RenderSettings settings;
    settings.width = 320;
    settings.height = 240;
    settings.spp = 2;
    aaf::io::write_aovs(aaf::trace::render_scene("grids", settings), (dir / "base.exr").string());
    for (int frame = 1; frame <= 40; ++frame) {
        char name[32];
        std::snprintf(name, sizeof name, "in.%04d.exr", frame);
        fs::copy_file(dir / "base.exr", dir / name);
    }
    const std::string in = (dir / "in.####.exr").string(), out = (dir / "out.####.exr").string();
    rusage usage{};
    REQUIRE(run_aaf("filter aaf " + in + " -o " + out + " --frames 1-4 --progress none").exit_code == 0);
    getrusage(RUSAGE_CHILDREN, &usage);
    const long peak_4_kb = usage.ru_maxrss;
    REQUIRE(run_aaf("filter aaf " + in + " -o " + out + " --frames 1-40 --progress none").exit_code == 0);
    getrusage(RUSAGE_CHILDREN, &usage);  // the largest child so far
    const long peak_40_kb = usage.ru_maxrss;
    INFO("peak RSS: 4 frames " << peak_4_kb << " KB, 40 frames " << peak_40_kb << " KB");
    CHECK(peak_40_kb < peak_4_kb + 50 * 1024);
}
