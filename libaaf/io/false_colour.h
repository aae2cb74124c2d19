#pragma once

#include <string>
#include <vector>

#include "aaf/core/math/vec3.h"

namespace aaf::io {

/// The false-colour ramp of previews and heatmaps for t in [0, 1] (clamped):
/// dark blue, blue, green, yellow, red, piecewise linear.
Vec3 false_colour(float t);

/// Writes 8-bit RGB from interleaved floats in [0, 1] as PNG, or JPEG when
/// `path` ends in .jpg or .jpeg (OpenImageIO quantises), under a temporary
/// name renamed into place. Throws aaf::Error.
void write_png(const std::vector<float> &rgb, int width, int height, const std::string &path);

}  // namespace aaf::io
