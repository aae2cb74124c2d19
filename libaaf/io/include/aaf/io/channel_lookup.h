#pragma once

#include <string>

#include "aaf/core/contract/aov_set.h"

namespace aaf::io {

/// `name` as `image` holds it: itself when present, else, for a channel of
/// the contract (aov_contract.h), the channel another renderer writes for
/// the same role (the beauty's R as Blender's ViewLayer.Combined.R or
/// Arnold's RGBA.R, shadow.V under a view-layer prefix), else `name` (the
/// caller names it missing). What `aaf compare` and `aaf preview` read for
/// a channel the user names.
std::string resolve_channel(const std::string &name, const AovSet &image);

}  // namespace aaf::io
