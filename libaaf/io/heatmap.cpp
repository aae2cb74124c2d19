#include "aaf/io/heatmap.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "aaf/core/util/error.h"
#include "aaf/io/exr_io.h"
#include "false_colour.h"
#include "formats_module.h"
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

/// Whether pixel (x, y) of the crop is compared: every pixel without a mask.
struct ComparedPixels {
    const ConstPlaneView &mask;
    PixelRect rect;
    bool operator()(int x, int y) const { return !mask.valid() || mask(rect.x + x, rect.y + y) != 0; }
};

/// Adds "error.rms" (the per-pixel RMS over the region's channels, 0 outside
/// the mask) and, with a mask, "error.compared" to `errors`; returns the
/// colour scale: the 99th percentile of the finite compared errors, so a few
/// fireflies do not wash out the map (1 when there are none above 0).
float add_rms_errors(const AovSet &test, const AovSet &reference, const CompareOptions &region,
                     const ComparedPixels &compared, AovSet &errors) {
    const int width = errors.width(), height = errors.height();
    const PixelRect &rect = compared.rect;
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
    if (compared.mask.valid()) {
        PlaneView selected = errors.add_channel("error.compared");
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) selected(x, y) = compared(x, y) ? 1.0f : 0.0f;
    }
    return scale;
}

/// The PNG's interleaved RGB pixels: the false-coloured `error` (black where
/// not compared, white where not finite), a colour bar to its right and, when
/// the image is tall enough, the bar's labels. Sets `png_width`.
std::vector<float> heatmap_pixels(const ConstPlaneView &error, const ComparedPixels &compared, float scale,
                                  int &png_width) {
    const int width = error.width, height = error.height;
    const bool labels = height >= kLabelMinHeightPx;
    const int bar_x = width + kBarGapPx;
    png_width = bar_x + kBarWidthPx + (labels ? kBarGapPx + kLabelWidthPx : 0);
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
    return rgb;
}

}  // namespace

namespace formats {

float write_error_heatmap(const AovSet &test, const AovSet &reference, const CompareOptions &region,
                          const std::string &png_path) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw Error(png_path + ": heatmap images differ in size");
    if (heatmap_exr_path(png_path) == png_path)
        throw Error(png_path + ": the heatmap PNG needs a name that does not end in .exr");
    const PixelRect rect = region.crop.value_or(PixelRect{0, 0, test.width(), test.height()});
    if (!rect_within(rect, test.width(), test.height()))
        throw InputError(png_path + ": the crop lies outside the image");
    const ConstPlaneView &mask = region.mask;
    if (mask.valid() && (mask.width != test.width() || mask.height != test.height()))
        throw Error(png_path + ": the mask differs in size from the images");
    const ComparedPixels compared{mask, rect};

    AovSet errors(rect.width, rect.height);
    const float scale = add_rms_errors(test, reference, region, compared, errors);
    int png_width = 0;
    const std::vector<float> rgb =
        heatmap_pixels(std::as_const(errors).channel("error.rms"), compared, scale, png_width);

    const std::string description = "RMS error over " + std::to_string(region.channels.size()) +
                                    " channels, colour bar 0 to " + short_number(scale) +
                                    (mask.valid() ? ", masked-out pixels black" : "");
    OIIO::ImageSpec png_spec(png_width, rect.height, 3, OIIO::TypeDesc::UINT8);
    png_spec.attribute("ImageDescription", description);
    write_image_atomically(png_path, "png", png_spec, rgb.data());

    errors.attributes["aaf:heatmap:max"] = scale;
    errors.attributes["aaf:heatmap:crop"] = std::to_string(rect.x) + "," + std::to_string(rect.y) + "," +
                                            std::to_string(rect.width) + "," + std::to_string(rect.height);
    errors.attributes["ImageDescription"] = description;
    write_aovs(errors, heatmap_exr_path(png_path));
    return scale;
}

}  // namespace formats

}  // namespace aaf::io
