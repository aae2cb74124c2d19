#include "aaf/io/preview.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <algorithm>
#include <cmath>
#include <limits>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"
#include "default_ocio_config.h"
#include "false_colour.h"
#include "formats_module.h"

namespace OCIO = OCIO_NAMESPACE;

namespace aaf::io {

namespace {

/// The config of `options`, $OCIO or the embedded one, and its name.
OCIO::ConstConfigRcPtr load_config(const PreviewOptions &options, std::string &name) {
    if (!options.ocio_config.empty()) {
        name = options.ocio_config;
        if (!std::ifstream(options.ocio_config))
            throw InputError(options.ocio_config + ": cannot read the OpenColorIO config");
        try {
            return OCIO::Config::CreateFromFile(options.ocio_config.c_str());
        } catch (const OCIO::Exception &e) {
            throw InputError(options.ocio_config + ": not an OpenColorIO config: " + e.what());
        }
    }
    if (const char *env = std::getenv("OCIO"); env && *env) {
        name = env;
        return OCIO::Config::CreateFromEnv();
    }
    name = "embedded aaf-default";
    std::istringstream text(kDefaultOcioConfig);
    return OCIO::Config::CreateFromStream(text);
}

/// `name` when it is one of `count` names of `name_at`, else aaf::Error listing them.
template <typename NameAt>
void check_known(const std::string &what, const std::string &name, int count, const NameAt &name_at) {
    std::string known;
    for (int i = 0; i < count; ++i) {
        if (name == name_at(i)) return;
        known += std::string(known.empty() ? "" : ", ") + name_at(i);
    }
    throw Error("unknown OpenColorIO " + what + " " + quoted(name) + " (the config has " + known + ")");
}

/// The CPU processor from the input space to the display/view of `options`.
OCIO::ConstCPUProcessorRcPtr display_processor(const PreviewOptions &options, std::string &config_name) {
    OCIO::ConstConfigRcPtr config = load_config(options, config_name);
    const std::string display = options.display.empty() ? config->getDefaultDisplay() : options.display;
    check_known("display", display, config->getNumDisplays(), [&](int i) { return config->getDisplay(i); });
    const std::string view = options.view.empty() ? config->getDefaultView(display.c_str()) : options.view;
    check_known("view", view, config->getNumViews(display.c_str()),
                [&](int i) { return config->getView(display.c_str(), i); });
    if (!options.input_space.empty())
        check_known("colour space", options.input_space, config->getNumColorSpaces(),
                    [&](int i) { return config->getColorSpaceNameByIndex(i); });
    std::string input = options.input_space;
    if (input.empty()) {
        OCIO::ConstColorSpaceRcPtr linear = config->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
        if (!linear) throw OCIO::Exception("the config has no scene_linear role (give --colorspace)");
        input = linear->getName();
    }
    OCIO::DisplayViewTransformRcPtr transform = OCIO::DisplayViewTransform::Create();
    transform->setSrc(input.c_str());
    transform->setDisplay(display.c_str());
    transform->setView(view.c_str());
    return config->getProcessor(transform)->getDefaultCPUProcessor();
}

/// The input lacks the channel: an input error, naming the file read.
void check_has_channel(const AovSet &aovs, const std::string &name, const std::string &source) {
    if (!aovs.has_channel(name)) throw InputError(source + ": no channel " + quoted(name) + " to preview");
}

}  // namespace

namespace formats {

void write_false_colour_png(const AovSet &aovs, const std::string &channel, const std::string &path,
                            float low, float high, const std::string &source_path) {
    check_has_channel(aovs, channel, source_path.empty() ? path : source_path);
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

void check_display_view(const PreviewOptions &options) {
    std::string config_name;
    try {
        display_processor(options, config_name);
    } catch (const OCIO::Exception &e) {
        throw Error("OpenColorIO: " + std::string(e.what()));
    }
}

std::string write_preview_png(const AovSet &aovs, const std::vector<std::string> &channels,
                              const std::string &path, const PreviewOptions &options) {
    if (channels.size() != 1 && channels.size() != 3)
        throw Error(path + ": a preview needs one or three channels");
    std::vector<ConstPlaneView> planes;
    // Data (P, N, distances, Arnold's P.R) is shown as stored; only colour
    // goes through the display transform.
    const std::vector<bool> colour_mask = colour_channels(aovs);
    bool colour = true;
    for (const std::string &name : channels) {
        check_has_channel(aovs, name, options.source_path.empty() ? path : options.source_path);
        planes.push_back(aovs.channel(name));
        colour = colour && colour_mask[aovs.index_of(name)];
    }
    // Place the data window inside the display window (cropping what lies outside).
    PixelWindow data = options.data_window, shown = options.display_window;
    if (shown.width <= 0 || shown.height <= 0) data = shown = {0, 0, aovs.width(), aovs.height()};
    const float scale = std::exp2(options.exposure_stops);
    std::vector<float> rgb(std::size_t(shown.width) * shown.height * 3, 0.0f);
    for (int y = 0; y < shown.height; ++y)
        for (int x = 0; x < shown.width; ++x) {
            const int source_x = x + shown.x - data.x, source_y = y + shown.y - data.y;
            if (source_x < 0 || source_y < 0 || source_x >= aovs.width() || source_y >= aovs.height())
                continue;
            for (int c = 0; c < 3; ++c) {
                const float value = planes[planes.size() == 3 ? c : 0](source_x, source_y) * scale;
                rgb[(std::size_t(y) * shown.width + x) * 3 + c] = std::isfinite(value) ? value : 0.0f;
            }
        }
    std::string config_name;
    if (colour) {
        try {
            OCIO::PackedImageDesc image(rgb.data(), shown.width, shown.height, 3);
            display_processor(options, config_name)->apply(image);
        } catch (const OCIO::Exception &e) {
            throw Error(path + ": OpenColorIO: " + e.what());
        }
    }
    // Data values are written as they are; the PNG writer clamps to [0, 1].
    for (float &value : rgb) value = std::clamp(value, 0.0f, 1.0f);
    write_png(rgb, shown.width, shown.height, path);
    return config_name;
}

}  // namespace formats

}  // namespace aaf::io
