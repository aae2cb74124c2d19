#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "aaf/io/exr_io.h"

#include "../scratch_dir.h"

using namespace aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

// Wide enough that a strip (about 4 MiB, a multiple of 32 rows) holds 32
// rows, so 75 rows are read and written as strips of 32, 32 and 11.
constexpr int kWidth = 2048, kHeight = 75, kChannels = 12;
constexpr int kOriginX = 3, kOriginY = -5;  // a data window off the origin

/// A value per pixel and channel that no shifted row, column or channel repeats.
float pattern(int x, int y, int c) {
    return float(c) * 1000.0f + float(y) * 7.0f + float(x) * 0.001f;
}

/// Writes the pattern with OpenImageIO itself, scanlines or 64x64 tiles.
std::vector<float> write_source(const std::string &path, bool tiled) {
    OIIO::ImageSpec spec(kWidth, kHeight, kChannels, OIIO::TypeDesc::FLOAT);
    spec.x = kOriginX;
    spec.y = kOriginY;
    spec.full_x = 0;
    spec.full_y = 0;
    spec.full_width = kWidth + 10;
    spec.full_height = kHeight + 10;
    spec.channelnames.clear();
    for (int c = 0; c < kChannels; ++c) spec.channelnames.push_back("layer.c" + std::to_string(10 + c));
    if (tiled) {
        spec.tile_width = 64;
        spec.tile_height = 64;
    }
    spec.attribute("compression", "zip");
    std::vector<float> pixels(std::size_t(kWidth) * kHeight * kChannels);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            for (int c = 0; c < kChannels; ++c)
                pixels[(std::size_t(y) * kWidth + std::size_t(x)) * kChannels + std::size_t(c)] =
                    pattern(x, y, c);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    REQUIRE(out);
    REQUIRE(out->open(path, spec));
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(out->close());
    return pixels;
}

}  // namespace

TEST_CASE("EXR pixels go through in strips bit-exact: several strips, a data window off the origin, tiles",
          "[io][strips]") {
    const bool tiled = GENERATE(false, true);
    const fs::path dir = scratch_dir(tiled ? "strips_tiled" : "strips_scanline");
    const std::string source = (dir / "source.exr").string(), copy = (dir / "copy.exr").string();
    const std::vector<float> pixels = write_source(source, tiled);

    io::ImageLayout layout;
    const AovSet aovs = io::read_aovs(source, &layout);
    REQUIRE(aovs.width() == kWidth);
    REQUIRE(aovs.height() == kHeight);
    REQUIRE(aovs.channel_names().size() == std::size_t(kChannels));
    // Every row of every strip lands in its own row of its own plane.
    std::size_t wrong = 0;
    for (int c = 0; c < kChannels; ++c) {
        const ConstPlaneView plane = aovs.channel("layer.c" + std::to_string(10 + c));
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) wrong += plane(x, y) != pattern(x, y, c);
    }
    CHECK(wrong == 0);

    io::WriteOptions options;
    options.layout = &layout;
    io::write_aovs(aovs, copy, options);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(copy);
    REQUIRE(in);
    const OIIO::ImageSpec &spec = in->spec();
    CHECK(spec.x == kOriginX);
    CHECK(spec.y == kOriginY);
    CHECK(spec.tile_width == (tiled ? 64 : 0));
    REQUIRE(spec.nchannels == kChannels);
    std::vector<float> back(pixels.size());
    REQUIRE(in->read_image(0, 0, 0, kChannels, OIIO::TypeDesc::FLOAT, back.data()));
    // Channels are stored sorted by name, as written: the same order here.
    CHECK(std::memcmp(back.data(), pixels.data(), pixels.size() * sizeof(float)) == 0);
}
