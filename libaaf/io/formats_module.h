#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/core/metrics/error_metrics.h"
#include "aaf/io/preview.h"
#include "other_formats.h"

namespace aaf::io {

/// What the aaf_formats module (OpenImageIO and OpenColorIO) does for
/// aaf_io: images of formats other than OpenEXR, PNG/JPEG pictures and colour
/// views. It is a shared library of its own, loaded on
/// first use, so that a command that only reads and writes OpenEXR does not
/// load OpenImageIO, OpenColorIO and their hundreds of dependencies.
/// The module and the library that loads it come from one build: the table
/// passes C++ types.
struct FormatsModule {
    OtherImage (*read_other_image)(const std::string &path, std::uint64_t memory_budget_bytes);
    bool (*is_readable_other_image)(const std::string &path, std::uint64_t memory_budget_bytes);
    std::string (*read_other_string_attribute)(const std::string &path, const std::string &name);
    void (*check_display_view)(const PreviewOptions &options);
    std::string (*write_preview_png)(const AovSet &aovs, const std::vector<std::string> &channels,
                                     const std::string &path, const PreviewOptions &options);
    void (*write_false_colour_png)(const AovSet &aovs, const std::string &channel, const std::string &path,
                                   float low, float high, const std::string &source_path);
    float (*write_error_heatmap)(const AovSet &test, const AovSet &reference, const CompareOptions &region,
                                 const std::string &png_path);
};

/// The module's entry point, a C symbol: returns its table.
#define AAF_FORMATS_ENTRY aaf_formats_module_v1
#define AAF_FORMATS_ENTRY_NAME "aaf_formats_module_v1"

/// The module's functions, loaded on the first call: libaaf_formats.so is
/// looked for beside the executable or library that holds aaf_io, then in the
/// install layout's library folder. Throws aaf::Error naming it when it
/// cannot be loaded.
const FormatsModule &formats_module();

/// The implementations inside the module.
namespace formats {
void check_display_view(const PreviewOptions &options);
std::string write_preview_png(const AovSet &aovs, const std::vector<std::string> &channels,
                              const std::string &path, const PreviewOptions &options);
void write_false_colour_png(const AovSet &aovs, const std::string &channel, const std::string &path,
                            float low, float high, const std::string &source_path);
float write_error_heatmap(const AovSet &test, const AovSet &reference, const CompareOptions &region,
                          const std::string &png_path);
}  // namespace formats

}  // namespace aaf::io
