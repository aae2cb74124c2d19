#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "aaf/core/contract/aov_set.h"

namespace aaf {

/// Channel name and how many of its values were NaN or infinite.
using NonFiniteCounts = std::vector<std::pair<std::string, std::size_t>>;

/// Replaces NaN and +-infinity in the named channels (those present) by
/// `replacement`, so one bad input value cannot spread through a filter's
/// gather, and returns the count per channel that had any.
NonFiniteCounts replace_non_finite(AovSet &aovs, const std::vector<std::string> &channels,
                                   float replacement = 0.0f);

}  // namespace aaf
