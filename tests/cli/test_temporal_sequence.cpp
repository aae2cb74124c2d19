// A temporal filter (ratio --temporal; render --filter ratio --filter-param
// temporal=true) reads the previous frame's output. Its frames must record
// the inputs their history reads, and a sequence made in several runs (in
// chunks, or resumed after a kill) must equal one uninterrupted run byte for
// byte.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "aaf/io/exr_io.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

const std::string kSize = " --width 24 --height 16 --spp 4 --progress none";

std::string bytes_of(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string frame_file(const fs::path &dir, const std::string &prefix, int frame) {
    return (dir / (prefix + ".000" + std::to_string(frame) + ".exr")).string();
}

std::string string_attribute(const std::string &path, const std::string &name) {
    const aaf::AovSet aovs = aaf::io::read_aovs(path);
    auto it = aovs.attributes.find(name);
    return it == aovs.attributes.end() ? "(none)" : std::get<std::string>(it->second);
}

/// Renders the ratio and motion inputs of frames `frames` into `dir`/in.####.exr.
void render_inputs(const fs::path &dir, const std::string &frames, const std::string &options = "") {
    REQUIRE(run_aaf("render grids --aovs ratio,motion --frames " + frames + kSize + options + " -o " +
                    (dir / "in.####.exr").string())
                .exit_code == 0);
}

aaf_test::RunResult filter_temporal(const fs::path &dir, const std::string &out, const std::string &options) {
    return run_aaf("filter ratio --temporal " + (dir / "in.####.exr").string() + " -o " +
                   (dir / (out + ".####.exr")).string() + " --progress jsonl" + options);
}

/// The number of frames a `--progress jsonl` run reports with `status`.
int count_status(const aaf_test::RunResult &result, const std::string &status) {
    int count = 0;
    const std::string key = "\"status\":\"" + status + "\"";
    for (std::size_t at = result.output.find(key); at != std::string::npos;
         at = result.output.find(key, at + 1))
        ++count;
    return count;
}

void require_same_bytes(const fs::path &dir, const std::string &a, const std::string &b, int first,
                        int last) {
    for (int frame = first; frame <= last; ++frame) {
        INFO(a << " and " << b << ", frame " << frame);
        const std::string bytes = bytes_of(frame_file(dir, a, frame));
        REQUIRE_FALSE(bytes.empty());
        CHECK(bytes == bytes_of(frame_file(dir, b, frame)));
    }
}

}  // namespace

TEST_CASE(
    "CLI: a temporal frame records the inputs its history reads, so --skip-existing redoes it when an "
    "earlier frame's input changed",
    "[cli][sequence][temporal]") {
    const fs::path dir = scratch_dir("temporal_provenance");
    render_inputs(dir, "1-3");
    REQUIRE(filter_temporal(dir, "out", "").exit_code == 0);
    // What each frame depends on: frame 1 none besides its own input, frame 3 frames 1 and 2.
    CHECK(string_attribute(frame_file(dir, "out", 1), "aaf:provenance:history") == "(none)");
    CHECK(string_attribute(frame_file(dir, "out", 3), "aaf:provenance:history") == "1-2");
    const auto rerun = filter_temporal(dir, "out", " --skip-existing");
    CHECK(count_status(rerun, "skipped") == 3);

    // Frame 1's input changes (another seed): every frame reads it, so none is up to date.
    REQUIRE(run_aaf("render grids --aovs ratio,motion --frame 1 --seed 7" + kSize + " -o " +
                    frame_file(dir, "in", 1))
                .exit_code == 0);
    const auto redone = filter_temporal(dir, "out", " --skip-existing");
    CHECK(count_status(redone, "ok") == 3);
    REQUIRE(filter_temporal(dir, "fresh", "").exit_code == 0);
    require_same_bytes(dir, "fresh", "out", 1, 3);

    // Without --temporal a frame reads its own input only: frame 1's change leaves frames 2 and 3 up to date.
    REQUIRE(run_aaf("filter ratio " + (dir / "in.####.exr").string() + " -o " +
                    (dir / "plain.####.exr").string() + " --progress none")
                .exit_code == 0);
    CHECK(string_attribute(frame_file(dir, "plain", 3), "aaf:provenance:history") == "(none)");
    REQUIRE(run_aaf("render grids --aovs ratio,motion --frame 1 --seed 8" + kSize + " -o " +
                    frame_file(dir, "in", 1))
                .exit_code == 0);
    const auto plain = run_aaf("filter ratio " + (dir / "in.####.exr").string() + " -o " +
                               (dir / "plain.####.exr").string() + " --progress jsonl --skip-existing");
    CHECK(count_status(plain, "ok") == 1);
    CHECK(count_status(plain, "skipped") == 2);
}

TEST_CASE(
    "CLI: a temporal sequence made in chunks or resumed after a kill equals one uninterrupted run byte "
    "for byte",
    "[cli][sequence][temporal]") {
    const fs::path dir = scratch_dir("temporal_chunks");

    SECTION("aaf filter ratio --temporal") {
        render_inputs(dir, "1-4");
        REQUIRE(filter_temporal(dir, "whole", "").exit_code == 0);
        // The history changes the image: frame 3 differs from its filter without --temporal.
        REQUIRE(run_aaf("filter ratio --frames 3-3 --progress none " + (dir / "in.####.exr").string() +
                        " -o " + (dir / "plain.####.exr").string())
                    .exit_code == 0);
        const aaf::AovSet with = aaf::io::read_aovs(frame_file(dir, "whole", 3));
        const aaf::AovSet without = aaf::io::read_aovs(frame_file(dir, "plain", 3));
        const float *a = with.channel("R").data, *b = without.channel("R").data;
        CHECK(std::vector<float>(a, a + with.pixel_count()) !=
              std::vector<float>(b, b + without.pixel_count()));

        // Two chunks, the second first.
        REQUIRE(filter_temporal(dir, "chunks", " --frames 3-4").exit_code == 0);
        REQUIRE(filter_temporal(dir, "chunks", " --frames 1-2").exit_code == 0);
        require_same_bytes(dir, "whole", "chunks", 1, 4);
        // Every other frame: each one's history is still its predecessor on disk.
        REQUIRE(filter_temporal(dir, "odd", " --frames 1-4x2").exit_code == 0);
        CHECK(bytes_of(frame_file(dir, "odd", 3)) == bytes_of(frame_file(dir, "whole", 3)));

        // A run killed during frame 3: frame 3 cut short, frame 4 never written.
        fs::copy_file(frame_file(dir, "whole", 1), frame_file(dir, "resumed", 1));
        fs::copy_file(frame_file(dir, "whole", 2), frame_file(dir, "resumed", 2));
        const std::string third = bytes_of(frame_file(dir, "whole", 3));
        std::ofstream(frame_file(dir, "resumed", 3), std::ios::binary) << third.substr(0, third.size() / 2);
        const auto resumed = filter_temporal(dir, "resumed", " --skip-existing");
        REQUIRE(resumed.exit_code == 0);
        CHECK(count_status(resumed, "skipped") == 2);
        require_same_bytes(dir, "whole", "resumed", 1, 4);
    }

    SECTION("aaf render --filter ratio --filter-param temporal=true") {
        const std::string render = "render grids --filter ratio --filter-param temporal=true" + kSize;
        const auto whole = run_aaf(render + " --frames 1-3 -o " + (dir / "whole.####.exr").string());
        REQUIRE(whole.exit_code == 0);
        CHECK(string_attribute(frame_file(dir, "whole", 3), "aaf:provenance:history") == "1-2");
        REQUIRE(run_aaf(render + " --frames 2-3 -o " + (dir / "chunks.####.exr").string()).exit_code == 0);
        REQUIRE(run_aaf(render + " --frames 1-1 -o " + (dir / "chunks.####.exr").string()).exit_code == 0);
        require_same_bytes(dir, "whole", "chunks", 1, 3);
        REQUIRE(
            run_aaf(render + " --frames 3-3 --threads 1 -o " + (dir / "alone.####.exr").string()).exit_code ==
            0);
        CHECK(bytes_of(frame_file(dir, "alone", 3)) == bytes_of(frame_file(dir, "whole", 3)));
    }
}
