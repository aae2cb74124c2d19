#include "aaf/io/heatmap.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "aaf/core/error.h"
#include "aaf/io/exr_io.h"
#include "false_colour.h"
#include "image_writer.h"

namespace aaf::io {

namespace {

constexpr int kBarWidthPx = 16;
constexpr int kBarGapPx = 4;
constexpr int kLabelFontPx = 12;
// Room for "0.000123" at 12 px (about 0.6 em per glyph) plus a margin.
constexpr int kLabelWidthPx = 64;
// Labels only where the bar has room for both without overlapping.
constexpr int kLabelMinHeightPx = 3 * kLabelFontPx;

std::string short_number(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", double(value));
    return text;
}

/// Draws `text` into the interleaved RGB `pixels`; false (and nothing drawn)
/// when OpenImageIO cannot render it, e.g. without the font.
bool draw_label(std::vector<float> &pixels, int width, int height, int x, int y, const std::string &text,
                OIIO::ImageBufAlgo::TextAlignY align) {
    OIIO::ImageBuf buffer(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT), pixels.data());
    const float white[3] = {1.0f, 1.0f, 1.0f};
    const bool ok = OIIO::ImageBufAlgo::render_text(buffer, x, y, text, kLabelFontPx, "DejaVuSans",
                                                    OIIO::cspan<float>(white),
                                                    OIIO::ImageBufAlgo::TextAlignX::Left, align);
    if (!ok) (void)buffer.geterror();  // clears the message; the scale is in the metadata anyway
    return ok;
}

}  // namespace

std::string heatmap_exr_path(const std::string &png_path) {
    return std::filesystem::path(png_path).replace_extension(".exr").string();
}

float write_error_heatmap(const AovSet &test, const AovSet &reference, const CompareOptions &region,
                          const std::string &png_path) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw Error(png_path + ": heatmap images differ in size");
    if (heatmap_exr_path(png_path) == png_path)
        throw Error(png_path + ": the heatmap PNG needs a name that does not end in .exr");
    const PixelRect rect = region.crop.value_or(PixelRect{0, 0, test.width(), test.height()});
    // Compared by subtraction: x + width can overflow int (2147483600 + 100).
    if (rect.width <= 0 || rect.height <= 0 || rect.x < 0 || rect.y < 0 || rect.x > test.width() ||
        rect.y > test.height() || rect.width > test.width() - rect.x || rect.height > test.height() - rect.y)
        throw Error(png_path + ": the crop lies outside the image");
    const ConstPlaneView &mask = region.mask;
    if (mask.valid() && (mask.width != test.width() || mask.height != test.height()))
        throw Error(png_path + ": the mask differs in size from the images");
    const int width = rect.width, height = rect.height;
    auto compared = [&](int x, int y) { return !mask.valid() || mask(rect.x + x, rect.y + y) != 0; };

    AovSet errors(width, height);
    PlaneView error = errors.add_channel("error.rms");
    for (const std::string &name : region.channels) {
        const ConstPlaneView a = test.channel(name), b = reference.channel(name);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const float d = a(rect.x + x, rect.y + y) - b(rect.x + x, rect.y + y);
                error(x, y) += d * d / float(region.channels.size());
            }
    }
    std::vector<float> finite;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            error(x, y) = compared(x, y) ? std::sqrt(error(x, y)) : 0.0f;
            if (compared(x, y) && std::isfinite(error(x, y))) finite.push_back(error(x, y));
        }
    float scale = 1.0f;
    if (!finite.empty()) {
        auto nth = finite.begin() + std::ptrdiff_t(0.99 * double(finite.size() - 1));
        std::nth_element(finite.begin(), nth, finite.end());
        scale = *nth > 0 ? *nth : 1.0f;
    }
    if (mask.valid()) {
        PlaneView selected = errors.add_channel("error.compared");
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) selected(x, y) = compared(x, y) ? 1.0f : 0.0f;
    }

    const bool labels = height >= kLabelMinHeightPx;
    const int bar_x = width + kBarGapPx;
    const int png_width = bar_x + kBarWidthPx + (labels ? kBarGapPx + kLabelWidthPx : 0);
    std::vector<float> rgb(std::size_t(png_width) * height * 3, 0.0f);
    auto put = [&](int x, int y, Vec3 c) {
        float *p = &rgb[(std::size_t(y) * png_width + x) * 3];
        p[0] = c.x;
        p[1] = c.y;
        p[2] = c.z;
    };
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float e = error(x, y);
            put(x, y,
                !compared(x, y) ? Vec3{0, 0, 0}
                                : (std::isfinite(e) ? false_colour(e / scale) : Vec3{1, 1, 1}));
        }
        // Colour bar: 0 at the bottom, the scale at the top.
        const Vec3 bar = false_colour(1.0f - float(y) / float(std::max(1, height - 1)));
        for (int x = bar_x; x < bar_x + kBarWidthPx; ++x) put(x, y, bar);
    }
    if (labels) {
        const int label_x = bar_x + kBarWidthPx + kBarGapPx;
        draw_label(rgb, png_width, height, label_x, 0, short_number(scale),
                   OIIO::ImageBufAlgo::TextAlignY::Top);
        draw_label(rgb, png_width, height, label_x, height - 1, "0", OIIO::ImageBufAlgo::TextAlignY::Bottom);
    }

    const std::string description = "RMS error over " + std::to_string(region.channels.size()) +
                                    " channels, colour bar 0 to " + short_number(scale) +
                                    (mask.valid() ? ", masked-out pixels black" : "");
    OIIO::ImageSpec png_spec(png_width, height, 3, OIIO::TypeDesc::UINT8);
    png_spec.attribute("ImageDescription", description);
    write_image_atomically(png_path, "png", png_spec, rgb.data());

    errors.attributes["aaf:heatmap:max"] = scale;
    errors.attributes["aaf:heatmap:crop"] = std::to_string(rect.x) + "," + std::to_string(rect.y) + "," +
                                            std::to_string(rect.width) + "," + std::to_string(rect.height);
    errors.attributes["ImageDescription"] = description;
    write_aovs(errors, heatmap_exr_path(png_path));
    return scale;
}

}  // namespace aaf::io
