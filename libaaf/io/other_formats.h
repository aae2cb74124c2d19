#pragma once

#include <cstdint>
#include <string>

#include "aaf/core/contract/aov_set.h"
#include "aaf/io/preview.h"

namespace aaf::io {

/// An image of a format other than OpenEXR (PNG, JPEG, TIFF...), read by
/// OpenImageIO: its first subimage's channels and attributes, its windows and
/// OpenImageIO's name of its format.
struct OtherImage {
    AovSet aovs;
    PixelWindow data_window, display_window;
    std::string format;
};

/// Reads `path` (not an OpenEXR file) as read_aovs() does, checking the
/// declared size against `memory_budget_bytes`. Throws aaf::InputError
/// "<path>: <problem>".
OtherImage read_other_image(const std::string &path, std::uint64_t memory_budget_bytes);

/// is_readable_image() for a file that is not OpenEXR; never throws.
bool is_readable_other_image(const std::string &path, std::uint64_t memory_budget_bytes);

/// read_string_attribute() for a file that is not OpenEXR; never throws.
std::string read_other_string_attribute(const std::string &path, const std::string &name);

}  // namespace aaf::io
