#include "aaf/io/preview.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "aaf/core/error.h"
#include "false_colour.h"

namespace OCIO = OCIO_NAMESPACE;

namespace aaf::io {

namespace {

/// Linear -> sRGB-encoded. OCIO 2.1 ships no built-in config, so the transform
/// is built directly: the inverse of the sRGB decoding curve, a power 2.4 with
/// offset 0.055 and a linear toe.
OCIO::ConstCPUProcessorRcPtr srgb_encoder() {
    OCIO::ExponentWithLinearTransformRcPtr curve = OCIO::ExponentWithLinearTransform::Create();
    const double gamma[4] = {2.4, 2.4, 2.4, 1.0};
    const double offset[4] = {0.055, 0.055, 0.055, 0.0};
    curve->setGamma(gamma);
    curve->setOffset(offset);
    curve->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
    return OCIO::Config::CreateRaw()->getProcessor(curve)->getDefaultCPUProcessor();
}

}  // namespace

void write_false_colour_png(const AovSet &aovs, const std::string &channel, const std::string &path,
                            float low, float high) {
    if (!aovs.has_channel(channel)) throw Error(path + ": no channel '" + channel + "' to preview");
    const ConstPlaneView values = aovs.channel(channel);
    if (low == high) {
        low = std::numeric_limits<float>::infinity();
        high = -low;
        for (int y = 0; y < aovs.height(); ++y)
            for (int x = 0; x < aovs.width(); ++x)
                if (values(x, y) != 0 && std::isfinite(values(x, y))) {
                    low = std::min(low, values(x, y));
                    high = std::max(high, values(x, y));
                }
        if (!(low < high)) high = low + 1;
    }
    std::vector<float> rgb(aovs.pixel_count() * 3, 0.0f);
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            const float v = values(x, y);
            if (v == 0 || !std::isfinite(v)) continue;
            const Vec3 colour = false_colour((v - low) / (high - low));
            float *pixel = &rgb[(std::size_t(y) * aovs.width() + x) * 3];
            pixel[0] = colour.x;
            pixel[1] = colour.y;
            pixel[2] = colour.z;
        }
    write_png(rgb, aovs.width(), aovs.height(), path);
}

void write_preview_png(const AovSet &aovs, const std::vector<std::string> &channels, const std::string &path,
                       float exposure_stops) {
    if (channels.size() != 1 && channels.size() != 3)
        throw Error(path + ": a preview needs one or three channels");
    std::vector<ConstPlaneView> planes;
    for (const std::string &name : channels) {
        if (!aovs.has_channel(name)) throw Error(path + ": no channel '" + name + "' to preview");
        planes.push_back(aovs.channel(name));
    }
    const float scale = std::exp2(exposure_stops);
    const int width = aovs.width(), height = aovs.height();
    std::vector<float> rgb(aovs.pixel_count() * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                float value = planes[planes.size() == 3 ? c : 0](x, y) * scale;
                rgb[(std::size_t(y) * width + x) * 3 + c] =
                    std::isfinite(value) ? std::max(0.0f, value) : 0.0f;
            }
    try {
        OCIO::PackedImageDesc image(rgb.data(), width, height, 3);
        srgb_encoder()->apply(image);
    } catch (const OCIO::Exception &e) {
        throw Error(path + ": colour conversion failed: " + e.what());
    }

    write_png(rgb, width, height, path);
}

}  // namespace aaf::io