#pragma once

#include <tbb/task_arena.h>

#include "aaf/core/error.h"

namespace aaf::cli {

/// Runs `work` on `threads` oneTBB workers (0 = all hardware threads).
/// Results never depend on the count; only the speed does.
template <typename Work>
void run_with_threads(int threads, const Work &work) {
    if (threads < 0) throw Error("--threads must be >= 0");
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
    arena.execute(work);
}

}  // namespace aaf::cli
