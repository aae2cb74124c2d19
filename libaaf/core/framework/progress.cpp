#include "aaf/core/framework/progress.h"

#include <algorithm>

namespace aaf {

void Progress::report(double fraction_done) {
    last_ = std::max(last_, std::clamp(fraction_done, 0.0, 1.0));  // a NaN leaves it unchanged
    if (monitor_ && !monitor_(last_)) throw Cancelled();
}

}  // namespace aaf
