#pragma once

#include <string>
#include <vector>

#include "aaf/core/aov_set.h"

namespace aaf::io {

/// Writes an 8-bit sRGB PNG preview of three linear channels (or one channel
/// shown as grey), scaled by 2^exposure_stops, encoded with OpenColorIO's
/// sRGB transfer function (IEC 61966-2-1). Written to a temporary name and
/// renamed. Throws aaf::Error "<path>: <problem>".
void write_preview_png(const AovSet &aovs, const std::vector<std::string> &channels, const std::string &path,
                       float exposure_stops = 0.0f);

/// Writes a false-colour PNG of one channel, as AAF Fig. 7 shows beta and n:
/// values in [low, high] run from dark blue through cyan, green and yellow to
/// red (clamped outside); pixels exactly 0 (not filtered, background) are
/// black. With low == high the channel's range over its non-zero pixels is used.
/// Written to a temporary name and renamed. Throws aaf::Error "<path>: <problem>".
void write_false_colour_png(const AovSet &aovs, const std::string &channel, const std::string &path,
                            float low = 0.0f, float high = 0.0f);

}  // namespace aaf::io
