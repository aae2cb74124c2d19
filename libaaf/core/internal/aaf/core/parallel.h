#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace aaf {

/// Calls `body(y)` for every row y in [0, height), rows in parallel on the
/// current oneTBB arena. Results must depend only on y so that they do not
/// depend on the thread count.
template <typename Body>
void parallel_for_rows(int height, const Body &body) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int> &rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) body(y);
    });
}

}  // namespace aaf
