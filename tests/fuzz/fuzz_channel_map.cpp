// libFuzzer harness: role mapping. The input is lines: the first byte says
// how many of them (mod 16) are channel names of a 2x1 AOV set, the others
// are `--map` specs ("role=name[,name...]"). set_override must accept a spec
// or throw aaf::Error; resolved() and every role's channels must then work.
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/aov_set.h"
#include "aaf/core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    if (size == 0) return 0;
    const std::size_t channel_count = data[0] % 16;
    std::istringstream lines(std::string(reinterpret_cast<const char *>(data) + 1, size - 1));
    aaf::AovSet aovs(2, 1);
    aaf::ChannelMap map;
    std::string line;
    for (std::size_t i = 0; std::getline(lines, line); ++i) {
        try {
            if (i < channel_count) {
                if (!aovs.has_channel(line)) aovs.add_channel(line, 1.0f);
            } else {
                map.set_override(line);
            }
        } catch (const aaf::Error &) {
        }
    }
    const aaf::ChannelMap resolved = map.resolved(aovs);
    for (const aaf::RoleInfo &info : aaf::role_table()) {
        const std::vector<std::string> &names = resolved.channels(info.role);
        if (names.empty()) __builtin_trap();  // every role keeps some names
    }
    (void)aaf::colour_channels(aovs, resolved);
    return 0;
}
