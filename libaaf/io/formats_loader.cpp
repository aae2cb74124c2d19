// aaf_io's side of the aaf_formats module: the loader and the public
// functions that the module implements.
#include <filesystem>
#include <mutex>

#include "aaf/core/util/error.h"
#include "aaf/io/heatmap.h"
#include "aaf/io/preview.h"
#include "formats_module.h"
#include "module_loader.h"

namespace aaf::io {

namespace {

const FormatsModule *load_formats_module() {
    return static_cast<const FormatsModule *>(load_module_table(
        "libaaf_formats.so", AAF_FORMATS_ENTRY_NAME,
        "OpenImageIO/OpenColorIO (PNG and JPEG pictures, colour views, images other than OpenEXR)"));
}

}  // namespace

const FormatsModule &formats_module() {
    static std::mutex mutex;
    static const FormatsModule *module = nullptr;
    const std::lock_guard<std::mutex> lock(mutex);
    if (!module) module = load_formats_module();  // a failure is reported again on the next call
    return *module;
}

void check_display_view(const PreviewOptions &options) {
    formats_module().check_display_view(options);
}

std::string write_preview_png(const AovSet &aovs, const std::vector<std::string> &channels,
                              const std::string &path, const PreviewOptions &options) {
    return formats_module().write_preview_png(aovs, channels, path, options);
}

void write_false_colour_png(const AovSet &aovs, const std::string &channel, const std::string &path,
                            float low, float high, const std::string &source_path) {
    formats_module().write_false_colour_png(aovs, channel, path, low, high, source_path);
}

std::string heatmap_exr_path(const std::string &png_path) {
    return std::filesystem::path(png_path).replace_extension(".exr").string();
}

float write_error_heatmap(const AovSet &test, const AovSet &reference, const CompareOptions &region,
                          const std::string &png_path) {
    return formats_module().write_error_heatmap(test, reference, region, png_path);
}

}  // namespace aaf::io
