// `aaf info` reads the header alone; `aaf info --stats` reads every pixel.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "run_aaf.h"

namespace fs = std::filesystem;
using aaf_test::run_aaf;
using aaf_test::RunResult;

namespace {

/// Overwrites the last `count` bytes of `path` (inside its last chunk's
/// compressed pixels; the header and the chunk table stay whole).
void damage_last_bytes(const fs::path &path, std::size_t count) {
    const auto size = fs::file_size(path);
    REQUIRE(size > count + 1024);
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(std::streamoff(size - count));
    for (std::size_t i = 0; i < count; ++i) file.put(char(0x5a));
}

/// A two-part EXR of 4 x 3 pixels: part "rgba" R, G, B as float, part "data"
/// (the same size) depth.Z as half.
void write_two_parts(const fs::path &path) {
    OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(4, 3, 3, OIIO::TypeDesc::FLOAT),
                                OIIO::ImageSpec(4, 3, 1, OIIO::TypeDesc::HALF)};
    specs[0].channelnames = {"R", "G", "B"};
    specs[0].attribute("name", "rgba");
    specs[1].channelnames = {"depth.Z"};
    specs[1].attribute("name", "data");
    const std::vector<float> colour(4 * 3 * 3, 0.5f), depth(4 * 3, 2.0f);
    auto out = OIIO::ImageOutput::create("openexr");
    REQUIRE(out);
    REQUIRE(out->open(path.string(), 2, specs));
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, colour.data()));
    REQUIRE(out->open(path.string(), specs[1], OIIO::ImageOutput::AppendSubimage));
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, depth.data()));
    REQUIRE(out->close());
}

}  // namespace

TEST_CASE("CLI: aaf info names each channel's storage, in other parts too, with or without --stats",
          "[cli][info]") {
    const fs::path path = aaf_test::scratch_dir("info_parts") / "parts.exr";
    write_two_parts(path);
    for (const char *stats : {"", "--stats "}) {
        const RunResult info = run_aaf(std::string("info ") + stats + path.string());
        INFO(info.output);
        REQUIRE(info.exit_code == 0);
        CHECK_THAT(info.output, Catch::Contains("part 1 'data': 4 x 3, depth.Z"));
        CHECK_THAT(info.output, Catch::Matches("[\\s\\S]*\\n  R +float[^\\n]*\\n[\\s\\S]*"));
        CHECK_THAT(info.output, Catch::Matches("[\\s\\S]*\\n  depth\\.Z +half[^\\n]*\\n[\\s\\S]*"));
    }
}

TEST_CASE("CLI: aaf info reads the header alone, aaf info --stats every pixel", "[cli][info]") {
    const fs::path dir = aaf_test::scratch_dir("info_header");
    const fs::path noisy = dir / "noisy.exr", damaged = dir / "damaged.exr";
    REQUIRE(run_aaf("render grids -o " + noisy.string() + " --width 32 --height 24 --spp 3").exit_code == 0);

    const RunResult header = run_aaf("info " + noisy.string());
    REQUIRE(header.exit_code == 0);
    CHECK_THAT(header.output, Catch::Contains("noisy.exr: 32 x 24, ") && Catch::Contains("shadow.d2max") &&
                                  Catch::Contains("aaf:light:sigma_m") && Catch::Contains("aaf      ready"));
    CHECK_THAT(header.output, !Catch::Contains("mean spp") && !Catch::Contains(" min "));

    const RunResult stats = run_aaf("info --stats " + noisy.string());
    REQUIRE(stats.exit_code == 0);
    CHECK_THAT(stats.output, Catch::Contains("mean spp over shaded pixels: 3") && Catch::Contains(" min ") &&
                                 Catch::Contains(" max ") && Catch::Contains("aaf      ready"));
    // Both say the same of every method: readiness is the header's.
    const auto methods = [](const std::string &output) { return output.substr(output.find("methods (")); };
    CHECK(methods(header.output) == methods(stats.output));

    // Pixels that do not decompress: the header still describes the file; --stats reports it.
    fs::copy_file(noisy, damaged, fs::copy_options::overwrite_existing);
    damage_last_bytes(damaged, 64);
    const RunResult quick = run_aaf("info " + damaged.string());
    CHECK(quick.exit_code == 0);
    CHECK_THAT(quick.output, Catch::Contains("damaged.exr: 32 x 24, "));
    const RunResult full = run_aaf("info --stats " + damaged.string());
    INFO(full.output);
    CHECK(full.exit_code == 3);
    CHECK_THAT(full.output, Catch::StartsWith("aaf: error: " + damaged.string() + ": "));
}
