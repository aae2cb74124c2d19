#include "aaf/io/channel_lookup.h"

#include <algorithm>
#include <vector>

#include "aaf/core/contract/aov_contract.h"

namespace aaf::io {

std::string resolve_channel(const std::string &name, const AovSet &image) {
    if (image.has_channel(name)) return name;
    const ChannelMap contract;
    const ChannelMap resolved = contract.resolved(image);
    for (const RoleInfo &info : role_table()) {
        const std::vector<std::string> &names = contract.channels(info.role);
        const auto at = std::find(names.begin(), names.end(), name);
        if (at != names.end()) return resolved.channels(info.role)[std::size_t(at - names.begin())];
    }
    return name;
}

}  // namespace aaf::io
