#pragma once

#include <string>

#include "aaf/core/aov_set.h"

namespace aaf::io {

/// Reads every channel of the first subimage of an image file (OpenEXR and any
/// other format OpenImageIO reads) as float (half channels are marked
/// Precision::Half, so writing them back keeps them half), with its header attributes: the
/// "aaf:" attributes and every other int, float, string or 3-vector attribute.
/// Throws aaf::Error "<path>: <problem>" when the file is missing, unreadable,
/// or has duplicate channel names.
AovSet read_aovs(const std::string &path);

/// True when `path` exists and its header reads back (e.g. a finished
/// output frame); never throws.
bool is_readable_image(const std::string &path);

/// Writes all channels as OpenEXR with ZIP compression, each as 32-bit float
/// or, where AovSet::precision says so, 16-bit half; and the
/// attributes as header attributes (no time stamp unless `aovs` carries a
/// "DateTime", so equal inputs give equal bytes). The file is written under a temporary
/// name in the same directory and renamed into place, so `path` never holds a
/// half-written image. Throws aaf::Error "<path>: <problem>".
void write_aovs(const AovSet &aovs, const std::string &path);

}  // namespace aaf::io
