#pragma once

#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"

namespace aaf::io {

/// A rectangle of pixels: an EXR data or display window.
struct PixelWindow {
    int x = 0, y = 0, width = 0, height = 0;
};

struct PreviewOptions {
    /// OpenColorIO config: this file, else $OCIO, else the project's embedded
    /// config (default_ocio_config.h).
    std::string ocio_config;
    std::string display, view;  ///< empty: the config's default display and its default view
    std::string input_space;    ///< empty: the config's scene_linear role
    float exposure_stops = 0;   ///< applied in linear light before the view
    /// Where the image's pixels sit (its data window) in the picture to write
    /// (the display window); both empty = the image as it is. Pixels of the
    /// display window outside the data window are black.
    PixelWindow data_window, display_window;
    /// The file `aovs` was read from, named when a channel is missing (the
    /// problem lies there); empty: the output path is named.
    std::string source_path;
};

/// Writes an 8-bit PNG preview of three channels (or one shown as grey).
/// Colour channels go through the OpenColorIO display/view of `options`;
/// data channels (positions, normals, visibility, distances) are never colour
/// converted: their values are written as they are, clamped to [0, 1].
/// Written to a temporary name and renamed. Returns the name of the
/// OpenColorIO config used ("" for data). Throws aaf::Error "<path>: <problem>",
/// or aaf::InputError "<source_path>: no channel 'NAME' to preview".
/// Checks the display, view and input colour space of `options` against the
/// config it names before any image is read: throws aaf::InputError when the
/// config file cannot be read or parsed (naming it), aaf::Error naming an
/// unknown display, view or colour space with the ones the config has.
void check_display_view(const PreviewOptions &options);

std::string write_preview_png(const AovSet &aovs, const std::vector<std::string> &channels,
                              const std::string &path, const PreviewOptions &options = {});

/// Writes a false-colour PNG of one channel, as AAF Fig. 7 shows beta and n:
/// values in [low, high] run from dark blue through cyan, green and yellow to
/// red (clamped outside); pixels exactly 0 (not filtered, background) are
/// black. With low == high the channel's range over its non-zero pixels is used.
/// Written to a temporary name and renamed. Throws aaf::Error "<path>: <problem>",
/// or aaf::InputError "<source_path>: no channel 'NAME' to preview" (the
/// output path when `source_path` is empty).
void write_false_colour_png(const AovSet &aovs, const std::string &channel, const std::string &path,
                            float low = 0.0f, float high = 0.0f, const std::string &source_path = "");

}  // namespace aaf::io
