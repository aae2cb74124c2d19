#pragma once

#include <OpenImageIO/imageio.h>

#include <string>

namespace aaf::io {

/// Writes interleaved float `pixels` described by `spec` with OpenImageIO's
/// `format` writer ("openexr", "png", ...) under a temporary name beside
/// `path`, then renames it into place; on failure removes the temporary and
/// throws aaf::Error "<path>: <problem>". OIIO converts to spec.format.
void write_image_atomically(const std::string &path, const char *format, const OIIO::ImageSpec &spec,
                            const float *pixels);

}  // namespace aaf::io
