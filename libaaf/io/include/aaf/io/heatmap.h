#pragma once

#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/core/metrics/error_metrics.h"

namespace aaf::io {

/// The EXR path written beside a heatmap PNG: `png_path` with the extension
/// `.exr` (`x.png` -> `x.exr`). Callers check it against their inputs.
std::string heatmap_exr_path(const std::string &png_path);

/// Writes the per-pixel error of `test` against `reference` over
/// `region.channels` (the root mean square over the channels of test - ref),
/// restricted to `region.crop` (the images cover the crop rectangle only) and
/// `region.mask` (pixels where the mask is 0 are masked out); other fields of
/// `region` are ignored. Two files:
/// - `png_path`: false colour from 0 (dark blue) to the 99th percentile of
///   the error over the unmasked pixels (red, larger values clamped), NaN/Inf
///   pixels in white, masked-out pixels in black, with a colour bar along the
///   right edge (bottom 0, top the 99th percentile). The scale is in the PNG's
///   `ImageDescription` and, when OpenImageIO can load the DejaVuSans font
///   (Debian: fonts-dejavu-core) and the image is at least 36 px high, written
///   as labels beside the bar (0 and the scale); without the font the label
///   column stays black;
/// - heatmap_exr_path(png_path): the error as channel `error.rms` (0 where
///   masked out), with a mask the channel `error.compared` (1 compared, 0
///   masked out), the scale as attribute `aaf:heatmap:max` and the crop as
///   `aaf:heatmap:crop` ("x,y,width,height").
/// Both are written under temporary names and renamed. Returns the scale.
/// Throws aaf::Error "<path>: <problem>" (sizes, crop outside the image, a
/// missing channel, an unwritable file).
float write_error_heatmap(const AovSet &test, const AovSet &reference, const CompareOptions &region,
                          const std::string &png_path);

}  // namespace aaf::io
