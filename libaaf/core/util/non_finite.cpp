#include "aaf/core/util/non_finite.h"

#include <cmath>

namespace aaf {

NonFiniteCounts replace_non_finite(AovSet &aovs, const std::vector<std::string> &channels,
                                   float replacement) {
    NonFiniteCounts counts;
    for (const std::string &name : channels) {
        if (!aovs.has_channel(name)) continue;
        PlaneView plane = aovs.channel(name);
        std::size_t count = 0;
        for (std::size_t i = 0; i < aovs.pixel_count(); ++i)
            if (!std::isfinite(plane.data[i])) {
                plane.data[i] = replacement;
                ++count;
            }
        if (count > 0) counts.emplace_back(name, count);
    }
    return counts;
}

}  // namespace aaf
