#pragma once

#include <string>
#include <vector>

#include "aaf/core/aov_set.h"

namespace aaf::io {

/// Writes the per-pixel error of `test` against `reference` over `channels`
/// (the root mean square over the channels of test - ref) twice:
/// - `png_path`: false colour from 0 (dark blue) to the 99th percentile of
///   the error (red, larger values clamped), NaN/Inf pixels in white, with a
///   colour bar along the right edge (bottom 0, top the 99th percentile);
/// - the same path with the extension `.exr`: the error as channel `error.rms`,
///   the scale as attribute `aaf:heatmap:max`.
/// Both are written under temporary names and renamed. Returns the scale.
/// Throws aaf::Error "<path>: <problem>".
float write_error_heatmap(const AovSet &test, const AovSet &reference,
                          const std::vector<std::string> &channels, const std::string &png_path);

}  // namespace aaf::io
