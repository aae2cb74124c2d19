#pragma once

#include <filesystem>

#include "aaf/core/contract/aov_set.h"
#include "aaf/io/exr_io.h"

namespace aaf_test {

/// Writes a 4x4 RGB image of one value.
inline void write_flat(const std::filesystem::path &path, float value) {
    aaf::AovSet image(4, 4);
    for (const char *c : {"R", "G", "B"}) image.add_channel(c, value);
    aaf::io::write_aovs(image, path.string());
}

}  // namespace aaf_test
