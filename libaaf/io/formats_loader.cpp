// aaf_io's side of the aaf_formats module: the loader and the public
// functions that the module implements.
#include <dlfcn.h>

#include <filesystem>
#include <mutex>

#include "aaf/core/util/error.h"
#include "aaf/io/heatmap.h"
#include "aaf/io/preview.h"
#include "formats_module.h"

namespace aaf::io {

namespace {

constexpr const char *kModuleFile = "libaaf_formats.so";

/// Folders to look in, in order: the folder of the executable or library
/// that holds this code (dladdr), the install layout's library folder
/// relative to it (bin/ -> lib/, and lib/pythonX.Y/site-packages/ -> lib/),
/// then this build's and the install prefix's library folders.
std::vector<std::filesystem::path> module_folders() {
    std::vector<std::filesystem::path> folders;
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void *>(&formats_module), &info) && info.dli_fname) {
        const std::filesystem::path here = std::filesystem::path(info.dli_fname).parent_path();
        folders.push_back(here);
        folders.push_back(here / AAF_FORMATS_BIN_TO_LIB);
        folders.push_back(here / ".." / "..");
    }
    folders.emplace_back(AAF_FORMATS_BUILD_DIR);
    folders.emplace_back(AAF_FORMATS_INSTALL_DIR);
    return folders;
}

const FormatsModule *load_module() {
    std::string why = "not found";
    for (const std::filesystem::path &folder : module_folders()) {
        std::error_code error;
        const std::filesystem::path file = folder / kModuleFile;
        if (!std::filesystem::is_regular_file(file, error)) continue;
        void *handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char *message = dlerror();
            why = message ? message : "cannot be loaded";
            continue;
        }
        using Entry = const FormatsModule *(*)();
        if (const auto entry = reinterpret_cast<Entry>(dlsym(handle, AAF_FORMATS_ENTRY_NAME))) return entry();
        why = file.string() + " has no " + AAF_FORMATS_ENTRY_NAME;
    }
    throw Error(std::string(kModuleFile) +
                ": cannot load aaf's OpenImageIO/OpenColorIO module (PNG and JPEG pictures, colour views, "
                "images other than OpenEXR): " +
                why + "; it belongs beside the aaf executable or in the install's lib folder");
}

}  // namespace

const FormatsModule &formats_module() {
    static std::mutex mutex;
    static const FormatsModule *module = nullptr;
    const std::lock_guard<std::mutex> lock(mutex);
    if (!module) module = load_module();  // a failure is reported again on the next call
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
