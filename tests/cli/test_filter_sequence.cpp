#include <catch2/catch.hpp>

#include <csignal>

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
    // printf and @ spellings of the same patterns.
    for (int frame = 1; frame <= 4; ++frame) fs::remove(dir / ("out.000" + std::to_string(frame) + ".exr"));
    REQUIRE(run_aaf("filter aaf " + (dir / "in.%04d.exr").string() + " -o " +
                    (dir / "out.@@@@.exr").string() + " --frames 3-4")
                .exit_code == 0);
    CHECK(outputs_present(dir) == std::vector<int>{3, 4});

    // A plain output for a sequence would receive every frame: refused, nothing written.
    const auto refused = run_aaf("filter aaf " + in + " -o " + (dir / "all.exr").string());
    CHECK(refused.exit_code == 2);  // usage
    CHECK_THAT(refused.output, Catch::Contains("all.exr"));
    CHECK(!fs::exists(dir / "all.exr"));

    // Usage errors exit 2, a pattern with no frames on disk is an input error (3).
    for (const char *usage : {"--frames 5-1", "--frames 1-4 --progress bogus", "--frames 1-4x0"}) {
        INFO(usage);
        CHECK(run_aaf("filter aaf " + in + " -o " + out + " " + std::string(usage)).exit_code == 2);
    }
    CHECK(run_aaf("filter aaf " + (dir / "in.0001.exr").string() + " -o " + (dir / "x.exr").string() +
                  " --frames 1-2")
              .exit_code == 2);
    CHECK(run_aaf("filter aaf " + (dir / "none.####.exr").string() + " -o " + out).exit_code == 3);
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

    // Without --skip-bad-frames the run stops at frame 3 (exit 3, an input
    // error) and the JSONL stream still ends with the frame's time and a summary.
    fs::remove(dir / "out.0004.exr");
    const auto stopped =
        run_aaf("filter aaf " + in + " -o " + out + " --frames 1-4 --skip-existing --progress=jsonl");
    CHECK(stopped.exit_code == 3);
    std::vector<nlohmann::json> events;
    std::istringstream stopped_lines(stopped.output);
    for (std::string line; std::getline(stopped_lines, line);)
        if (!line.empty() && line.front() == '{') events.push_back(nlohmann::json::parse(line));
    REQUIRE(events.size() == 5);  // start, frames 1-3, summary
    CHECK(events[3]["frame"] == 3);
    CHECK(events[3]["status"] == "failed");
    CHECK(events[3].contains("seconds"));
    CHECK(events[4]["event"] == "summary");
    CHECK(events[4]["failed"] == 1);
    CHECK(events[4]["not_run"] == 1);
    CHECK(!fs::exists(dir / "out.0004.exr"));

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
    CHECK(skipped == 2);
    CHECK(ok == 2);
}

TEST_CASE("filter: a run killed by SIGTERM mid-write leaves no partial or temporary file",
          "[cli][sequence]") {
    const fs::path dir = scratch_dir("filter_killed");
    render_sequence(dir);
    const std::string in = (dir / "in.####.exr").string(), out = (dir / "out.####.exr").string();
    // The test hook holds each finished temporary 3 s before its rename; the
    // kill lands while frame 1's temporary exists: the script waits for it to
    // appear (up to 60 s: a loaded machine starts the tool late), then kills.
    const fs::path script = dir / "kill.sh";
    std::ofstream(script) << "AAF_TEST_HOLD_BEFORE_RENAME_S=3 " << AAF_EXECUTABLE << " filter aaf " << in
                          << " -o " << out << " --frames 1-4 >/dev/null 2>&1 &\n"
                          << "pid=$!\nfor i in $(seq 1 1200); do ls -a " << dir.string()
                          << " | grep -q 'tmp-' && break; sleep 0.05; done\n"
                          << "ls -a " << dir.string() << " | grep -c 'tmp-' > " << (dir / "seen.txt").string()
                          << "\nkill -TERM $pid\nwait $pid\necho $? > " << (dir / "status.txt").string()
                          << "\n";
    REQUIRE(std::system(("bash " + script.string()).c_str()) == 0);
    int temporaries_seen = 0, status = 0;
    std::ifstream(dir / "seen.txt") >> temporaries_seen;
    std::ifstream(dir / "status.txt") >> status;
    CHECK(temporaries_seen == 1);  // the kill came mid-write
    CHECK(status == 128 + SIGTERM);
    CHECK(outputs_present(dir).empty());
    CHECK(!has_temporaries(dir));

    REQUIRE(run_aaf("filter aaf " + in + " -o " + out + " --frames 1-4 --skip-existing").exit_code == 0);
    CHECK(outputs_present(dir) == std::vector<int>{1, 2, 3, 4});
    CHECK(!has_temporaries(dir));
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
