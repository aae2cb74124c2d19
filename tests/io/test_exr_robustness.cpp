#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <string>

#include "aaf/core/util/error.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/preview.h"
#include "crafted_exr.h"

#include "../scratch_dir.h"

using namespace aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

/// The message read_aovs() throws for `path`, or "" when it reads.
std::string read_error(const std::string &path) {
    try {
        io::read_aovs(path);
    } catch (const InputError &e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("a truncated EXR is not a readable image, and reading it is an input error", "[io][robustness]") {
    const fs::path dir = scratch_dir("robust_truncated");
    const std::string path = (dir / "frame.exr").string();
    aaf_test::write_noise_exr(path, 64, 48, 3);
    REQUIRE(io::is_readable_image(path));
    aaf_test::truncate_to_half(path);
    CHECK(!io::is_readable_image(path));
    const std::string message = read_error(path);
    CHECK(message.rfind(path + ": ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
}

TEST_CASE("a header declaring 100000x100000 fails on the memory limit before allocating",
          "[io][robustness]") {
    const fs::path dir = scratch_dir("robust_huge_header");
    const std::string path = (dir / "huge.exr").string();
    aaf_test::write_noise_exr(path, 8, 8, 3);
    aaf_test::declare_size(path, 100000, 100000);
    CHECK(!io::is_readable_image(path));
    CHECK(read_error(path) ==
          path +
              ": declares 100000x100000 with 3 channels (112 GiB), over the memory limit of "
              "16 GiB (raise with --memory-limit-gb or AAF_MEMORY_LIMIT_GB)");
}

TEST_CASE("a 60 KB file declaring 8000x8000 fails before allocating the declared size", "[io][robustness]") {
    const fs::path dir = scratch_dir("robust_small_file_big_header");
    const std::string path = (dir / "small.exr").string();
    aaf_test::write_noise_exr(path, 64, 64, 4);
    CHECK(fs::file_size(path) < 80000);
    aaf_test::declare_size(path, 8000, 8000);
    CHECK(!io::is_readable_image(path));
    const std::string message = read_error(path);
    CHECK(message.rfind(path + ": ", 0) == 0);
    CHECK(message.find("truncated") != std::string::npos);
}

TEST_CASE("the memory budget can be lowered and raised, and names the file and the limit",
          "[io][robustness]") {
    const fs::path dir = scratch_dir("robust_budget");
    const std::string path = (dir / "frame.exr").string();
    aaf_test::write_noise_exr(path, 64, 64, 4);  // 64 KiB of float pixels
    io::set_memory_budget_bytes(32 << 10);
    const std::string message = read_error(path);
    io::set_memory_budget_bytes(0);
    CHECK(message ==
          path +
              ": declares 64x64 with 4 channels (6.1e-05 GiB), over the memory limit of 3.05e-05 GiB "
              "(raise with --memory-limit-gb or AAF_MEMORY_LIMIT_GB)");
    CHECK(io::memory_budget_bytes() == std::uint64_t(16) << 30);
    CHECK(read_error(path).empty());
}

TEST_CASE("a channel name with raw bytes is escaped, so the error stays one line", "[io][robustness]") {
    const fs::path dir = scratch_dir("robust_raw_channel_name");
    const std::string path = (dir / "raw.exr").string();
    const std::string raw = "\xff\nV";
    // Part 1 holds the raw-named channel at another size than part 0: reading
    // it for a filter fails with a message that quotes the name.
    OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(4, 4, 1, OIIO::TypeDesc::FLOAT),
                                OIIO::ImageSpec(2, 2, 1, OIIO::TypeDesc::FLOAT)};
    specs[0].channelnames = {"R"};
    specs[1].channelnames = {raw};
    specs[1].full_width = specs[1].full_height = 4;  // parts share the display window
    specs[0].attribute("oiio:subimagename", "rgba");
    specs[1].attribute("oiio:subimagename", "odd\tpart");
    const std::vector<float> pixels(16, 0.5f);
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path);
    REQUIRE(output);
    if (!output->open(path, 2, specs)) FAIL(output->geterror());
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(output->open(path, specs[1], OIIO::ImageOutput::AppendSubimage));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(output->close());

    io::ImageLayout layout;
    AovSet aovs = io::read_aovs(path, &layout);
    try {
        io::add_channels_from_other_parts(path, layout, {raw}, aovs);
        FAIL("read a part of another size");
    } catch (const InputError &e) {
        CHECK(std::string(e.what()) ==
              path +
                  ": channel '\\xff\\x0aV' is in part 'odd\\x09part' of 2x2, but the "
                  "first part is 4x4: AOVs must share one resolution");
    }
    try {
        aovs.channel(raw);
        FAIL("found a missing channel");
    } catch (const InputError &e) {
        CHECK(std::string(e.what()) == "missing channel '\\xff\\x0aV'");
    }
}

TEST_CASE("writing to a path that is a folder says so and leaves the folder alone", "[io][robustness]") {
    const fs::path dir = scratch_dir("robust_folder_output");
    const fs::path folder = dir / "out.exr";
    fs::create_directory(folder);
    AovSet aovs(4, 4);
    aovs.add_channel("R", 1.0f);
    try {
        io::write_aovs(aovs, folder.string());
        FAIL("wrote over a folder");
    } catch (const InputError &e) {
        CHECK(std::string(e.what()) == folder.string() + ": is a directory");
    }
    CHECK(fs::is_directory(folder));
    CHECK(fs::is_empty(folder));
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("a preview of a missing channel names the file it was read from", "[io][robustness]") {
    const fs::path dir = scratch_dir("robust_preview_missing");
    const std::string output = (dir / "preview.png").string();
    AovSet aovs(4, 4);
    aovs.add_channel("R", 0.5f);
    io::PreviewOptions options;
    options.source_path = "frame.exr";
    try {
        io::write_preview_png(aovs, {"nope\n"}, output, options);
        FAIL("previewed a missing channel");
    } catch (const InputError &e) {
        CHECK(std::string(e.what()) == "frame.exr: no channel 'nope\\x0a' to preview");
    }
    try {
        io::write_false_colour_png(aovs, "beta", output, 0, 1, "frame.exr");
        FAIL("previewed a missing channel");
    } catch (const InputError &e) {
        CHECK(std::string(e.what()) == "frame.exr: no channel 'beta' to preview");
    }
    CHECK(fs::is_empty(dir));
}

TEST_CASE("a non-EXR file declaring more pixels than its bytes can hold is refused before allocating",
          "[io][robustness]") {
    // Found by scripts/fuzz.sh: 26 bytes that OpenImageIO reads as a WebP of
    // 14898x10798 pixels; reading it allocated 3.2 GB before failing.
    const std::string path =
        std::string(AAF_SOURCE_DIR) + "/testdata/bad/fuzz_findings/read_aovs-webp_header_declaring_2_5GB.exr";
    CHECK_THROWS_AS(io::read_aovs(path), InputError);
    CHECK_THROWS_WITH(io::read_aovs(path), Catch::Contains("more than a 26-byte webp file can hold"));
    CHECK_FALSE(io::is_readable_image(path));
}

TEST_CASE("an EXR header without a channel list is refused before OpenEXR allocates from defaults",
          "[io][robustness]") {
    // Found by scripts/fuzz.sh: 830 bytes whose 'channels' name was mangled; reading took 2.1 GB.
    const std::string path = std::string(AAF_SOURCE_DIR) +
                             "/testdata/bad/fuzz_findings/read_aovs-header_without_channels_2_1GB.exr";
    CHECK_THROWS_AS(io::read_aovs(path), InputError);
    CHECK_THROWS_WITH(io::read_aovs(path), Catch::Contains("no 'channels' attribute"));
}
