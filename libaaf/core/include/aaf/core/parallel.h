#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "aaf/core/error.h"

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

/// Runs `work` on `threads` oneTBB workers (0 = all hardware threads).
/// Results never depend on the count; only the speed does. Throws
/// aaf::Error "--threads must be >= 0" (every command spells the option so)
/// for a negative count.
template <typename Work>
void run_with_threads(int threads, const Work &work) {
    if (threads < 0) throw Error("--threads must be >= 0");
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
    arena.execute(work);
}

}  // namespace aaf
