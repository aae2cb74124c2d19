#pragma once

namespace aaf::io {

/// The OpenColorIO config used when neither --ocio-config nor $OCIO names one
/// (OCIO 2.1 has no built-in configs): scene-linear Rec.709 in, one display
/// "sRGB" with the views "Standard" (the sRGB transfer function, IEC
/// 61966-2-1) and "Raw" (no conversion).
extern const char *const kDefaultOcioConfig;

}  // namespace aaf::io
