#pragma once

#include <string>
#include <vector>

#include "aaf/core/aov_contract.h"

namespace aaf::cli {

/// The default channel map with every `--map role=channel` override applied.
inline ChannelMap channel_map_from(const std::vector<std::string> &specs) {
    ChannelMap map;
    for (const std::string &spec : specs) map.set_override(spec);
    return map;
}

}  // namespace aaf::cli
