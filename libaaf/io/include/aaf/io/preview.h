#pragma once

#include <string>
#include <vector>

#include "aaf/core/aov_set.h"

namespace aaf::io {

/// Writes an 8-bit sRGB PNG preview of three linear channels (or one channel
/// shown as grey), scaled by 2^exposure_stops, encoded with OpenColorIO's
/// sRGB transfer function (IEC 61966-2-1). Written to a temporary name and
/// renamed. Throws aaf::Error "<path>: <problem>".
void write_preview_png(const AovSet &aovs, const std::vector<std::string> &channels,
                       const std::string &path, float exposure_stops = 0.0f);

}  // namespace aaf::io
