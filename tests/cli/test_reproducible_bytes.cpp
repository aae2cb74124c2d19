// Equal settings give equal bytes: no timing or run-specific option reaches
// an output's header, so a frame is the same file whichever run or chunk of
// a sequence made it.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "aaf/core/util/instruction_set.h"
#include "aaf/io/exr_io.h"
#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;

namespace {

std::string bytes_of(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("CLI: two renders of the same settings are byte-identical files, timings only on stderr",
          "[cli][render][provenance]") {
    const fs::path dir = scratch_dir("reproducible_render");
    for (const char *aovs : {"maaf6", "aaf", "ratio,motion"}) {
        INFO("--aovs " << aovs);
        const std::string render = "render room --width 24 --height 16 --spp 4 --aovs " + std::string(aovs);
        REQUIRE(run_aaf(render + " --progress none -o " + (dir / "a.exr").string()).exit_code == 0);
        const auto timed =
            run_aaf(render + " --progress lines --timings --threads 1 -o " + (dir / "b.exr").string());
        REQUIRE(timed.exit_code == 0);
        const std::string a = bytes_of(dir / "a.exr");
        REQUIRE_FALSE(a.empty());
        CHECK(a == bytes_of(dir / "b.exr"));
        CHECK_THAT(timed.output, Catch::Contains("aaf: timings: "));
    }
    // The maaf6 group's timings are printed, not stored.
    const auto timed =
        run_aaf("render room --width 24 --height 16 --spp 4 --aovs maaf6 --timings --progress none -o " +
                (dir / "c.exr").string());
    CHECK_THAT(timed.output, Catch::Contains("maaf6 sampling ") && Catch::Contains("pre-filtering "));
    const aaf::AovSet made = aaf::io::read_aovs((dir / "c.exr").string());
    for (const auto &entry : made.attributes) {
        INFO(entry.first);
        const std::string &name = entry.first;
        CHECK_FALSE((name.size() > 2 && name.compare(name.size() - 2, 2, "_s") == 0));  // no seconds
    }
}

TEST_CASE("CLI: a frame gives the same bytes whichever chunk of the sequence made it (render and filter)",
          "[cli][sequence][provenance]") {
    const fs::path dir = scratch_dir("reproducible_chunks");
    const std::string render = "render grids --width 24 --height 16 --spp 4 -o ";
    REQUIRE(run_aaf(render + (dir / "all.####.exr").string() + " --frames 1-3 --progress none").exit_code ==
            0);
    REQUIRE(run_aaf(render + (dir / "one.####.exr").string() +
                    " --frames 2-2 --progress lines --threads 1 --skip-existing")
                .exit_code == 0);
    const std::string rendered = bytes_of(dir / "all.0002.exr");
    REQUIRE_FALSE(rendered.empty());
    CHECK(rendered == bytes_of(dir / "one.0002.exr"));

    const std::string filter = "filter aaf " + (dir / "all.####.exr").string() + " -o ";
    REQUIRE(run_aaf(filter + (dir / "f_all.####.exr").string() + " --frames 1-3 --progress none").exit_code ==
            0);
    REQUIRE(run_aaf(filter + (dir / "f_one.####.exr").string() +
                    " --frames=2-2 --progress jsonl --threads 2 --skip-existing --skip-bad-frames")
                .exit_code == 0);
    REQUIRE(run_aaf(filter + (dir / "f_disk.####.exr").string() + " --progress none").exit_code == 0);
    const std::string filtered = bytes_of(dir / "f_all.0002.exr");
    REQUIRE_FALSE(filtered.empty());
    CHECK(filtered == bytes_of(dir / "f_one.0002.exr"));
    CHECK(filtered == bytes_of(dir / "f_disk.0002.exr"));  // every frame on disk, no --frames
}

TEST_CASE("CLI: a render gives the same file under every instruction set this CPU runs",
          "[cli][render][provenance][isa]") {
    const fs::path dir = scratch_dir("reproducible_isa");
    std::string first;
    for (aaf::InstructionSet set : aaf::kInstructionSets) {
        if (!aaf::cpu_supports(set)) continue;
        const std::string name = aaf::instruction_set_name(set);
        INFO("--isa " << name);
        const fs::path out = dir / (name + ".exr");
        // Every tracer group, so every channel's bits and every attribute count.
        REQUIRE(
            run_aaf("render studio --width 24 --height 16 --spp 4 --aovs all,maaf,isg,maaf6 --progress none "
                    "--isa " +
                    name + " -o " + out.string())
                .exit_code == 0);
        const std::string bytes = bytes_of(out);
        REQUIRE_FALSE(bytes.empty());
        if (first.empty()) first = bytes;
        CHECK(bytes == first);
    }
}
