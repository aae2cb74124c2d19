#include "aaf/core/thread_count.h"

#include <tbb/task_arena.h>

#include "aaf/core/error.h"

namespace aaf {

void run_with_threads(int threads, const std::function<void()> &work) {
    if (threads < 0) throw Error("--threads must be >= 0");
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
    arena.execute(work);
}

}  // namespace aaf
