#include "aaf/io/heatmap.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "aaf/core/error.h"
#include "aaf/io/exr_io.h"
#include "false_colour.h"

namespace aaf::io {

namespace {

constexpr int kBarWidthPx = 16;
constexpr int kBarGapPx = 4;

}  // namespace

float write_error_heatmap(const AovSet &test, const AovSet &reference,
                          const std::vector<std::string> &channels, const std::string &png_path) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw Error(png_path + ": heatmap images differ in size");
    const int width = test.width(), height = test.height();
    AovSet errors(width, height);
    PlaneView error = errors.add_channel("error.rms");
    for (const std::string &name : channels) {
        const ConstPlaneView a = test.channel(name), b = reference.channel(name);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const float d = a(x, y) - b(x, y);
                error(x, y) += d * d / float(channels.size());
            }
    }
    std::vector<float> finite;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            error(x, y) = std::sqrt(error(x, y));
            if (std::isfinite(error(x, y))) finite.push_back(error(x, y));
        }
    float scale = 1.0f;
    if (!finite.empty()) {
        auto nth = finite.begin() + std::ptrdiff_t(0.99 * double(finite.size() - 1));
        std::nth_element(finite.begin(), nth, finite.end());
        scale = *nth > 0 ? *nth : 1.0f;
    }

    const int png_width = width + kBarGapPx + kBarWidthPx;
    std::vector<float> rgb(std::size_t(png_width) * height * 3, 0.0f);
    auto put = [&](int x, int y, Vec3 c) {
        float *p = &rgb[(std::size_t(y) * png_width + x) * 3];
        p[0] = c.x;
        p[1] = c.y;
        p[2] = c.z;
    };
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x)
            put(x, y, std::isfinite(error(x, y)) ? false_colour(error(x, y) / scale) : Vec3{1, 1, 1});
        // Colour bar: 0 at the bottom, the scale at the top.
        const Vec3 bar = false_colour(1.0f - float(y) / float(std::max(1, height - 1)));
        for (int x = width + kBarGapPx; x < png_width; ++x) put(x, y, bar);
    }
    write_png(rgb, png_width, height, png_path);

    errors.attributes["aaf:heatmap:max"] = scale;
    errors.attributes["ImageDescription"] = std::string("RMS error over ") + std::to_string(channels.size()) +
                                            " channels, colour bar 0 to " + std::to_string(scale);
    write_aovs(errors, std::filesystem::path(png_path).replace_extension(".exr").string());
    return scale;
}

}  // namespace aaf::io
