// `aaf filter ratio` on files: a static sequence with and without --temporal
// (the pipeline hands each frame the previous frame's output), per-light layers
// read from the file.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/io/exr_io.h"
#include "run_aaf.h"

using namespace aaf;
using aaf_test::run_aaf;
using aaf_test::scratch_dir;
namespace fs = std::filesystem;

namespace {

float hash01(int x, int y, int salt) {
    std::uint32_t h =
        std::uint32_t(x) * 73856093u ^ std::uint32_t(y) * 19349663u ^ std::uint32_t(salt) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return float(h >> 8) / 16777216.0f;
}

/// Frame `frame` of a static floor under two lights at 1 sample per light:
/// a penumbra across the image, fresh noise each frame, zero motion.
AovSet frame_aovs(int frame, int width = 32, int height = 20) {
    AovSet aovs(width, height);
    const char *xyz[3] = {"X", "Y", "Z"}, *rgb[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        PlaneView p = aovs.add_channel(std::string("P.") + xyz[c]),
                  n = aovs.add_channel(std::string("N.") + xyz[c]);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                p(x, y) = c == 0 ? 0.01f * float(x) : c == 2 ? 0.01f * float(y) : 0.0f;
                n(x, y) = c == 1 ? 1.0f : 0.0f;
            }
    }
    std::fill_n(aovs.add_channel("pixel.size").data, aovs.pixel_count(), 0.01f);
    aovs.add_channel("motion.X");
    aovs.add_channel("motion.Y");
    for (const std::string prefix : {"ratio.", "ratio.L0.", "ratio.L1."})
        for (int c = 0; c < 3; ++c)
            for (const char *layer : {"U.", "S.", "Un."}) aovs.add_channel(prefix + layer + rgb[c]);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int light = 0; light < 2; ++light) {
                const std::string prefix = "ratio.L" + std::to_string(light) + ".";
                const bool visible = hash01(x, y, 10 * frame + light) < float(x) / float(width);
                const float weight = 1.0f + hash01(x, y, 1000 + 10 * frame + light);
                for (int c = 0; c < 3; ++c) {
                    const float colour = light == 0 ? 0.2f + 0.3f * float(c) : 0.8f - 0.2f * float(c);
                    const float values[3] = {colour, visible ? colour * weight : 0.0f, colour * weight};
                    const char *layers[3] = {"U.", "S.", "Un."};
                    for (int k = 0; k < 3; ++k) {
                        aovs.channel(prefix + layers[k] + rgb[c])(x, y) = values[k];
                        aovs.channel(std::string("ratio.") + layers[k] + rgb[c])(x, y) += values[k];
                    }
                }
            }
    aovs.attributes[attr::kRatioLights] = 2;
    return aovs;
}

double frame_difference(const std::string &a, const std::string &b) {
    const AovSet x = io::read_aovs(a), y = io::read_aovs(b);
    double sum = 0;
    for (const char *c : {"R", "G", "B"})
        for (std::size_t i = 0; i < x.pixel_count(); ++i)
            sum += std::pow(x.channel(c).data[i] - y.channel(c).data[i], 2);
    return std::sqrt(sum / double(3 * x.pixel_count()));
}

bool same_pixels(const std::string &a, const std::string &b) {
    const AovSet x = io::read_aovs(a), y = io::read_aovs(b);
    for (const char *c : {"R", "G", "B"})
        if (std::memcmp(x.channel(c).data, y.channel(c).data, x.pixel_count() * sizeof(float)) != 0)
            return false;
    return true;
}

}  // namespace

TEST_CASE(
    "aaf filter ratio --temporal: each frame blends with the previous output, frame 1 alone, with less "
    "flicker, for any thread count",
    "[cli][ratio]") {
    const fs::path dir = scratch_dir("cli_ratio_temporal");
    const int frames = 5;
    for (int f = 1; f <= frames; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "seq.%04d.exr", f);
        io::write_aovs(frame_aovs(f), (dir / name).string());
    }
    const std::string in = (dir / "seq.####.exr").string();
    auto out = [&](const char *which, int f) {
        char name[48];
        std::snprintf(name, sizeof name, "%s.%04d.exr", which, f);
        return (dir / name).string();
    };
    REQUIRE(run_aaf("filter ratio " + in + " -o " + (dir / "plain.####.exr").string() + " --progress none")
                .exit_code == 0);
    const auto temporal = run_aaf("filter ratio " + in + " -o " + (dir / "temporal.####.exr").string() +
                                  " --temporal --progress none");
    INFO(temporal.output);
    REQUIRE(temporal.exit_code == 0);
    REQUIRE(run_aaf("filter ratio " + in + " -o " + (dir / "one.####.exr").string() +
                    " --temporal --threads 1 --progress none")
                .exit_code == 0);
    CHECK(same_pixels(out("plain", 1), out("temporal", 1)));
    double flicker_plain = 0, flicker_temporal = 0;
    for (int f = 2; f <= frames; ++f) {
        CHECK_FALSE(same_pixels(out("plain", f), out("temporal", f)));
        CHECK(same_pixels(out("temporal", f), out("one", f)));
        flicker_plain += frame_difference(out("plain", f), out("plain", f - 1));
        flicker_temporal += frame_difference(out("temporal", f), out("temporal", f - 1));
    }
    CHECK(flicker_temporal < 0.6 * flicker_plain);
}
