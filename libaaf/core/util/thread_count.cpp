#include "aaf/core/util/thread_count.h"

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <optional>

#include "aaf/core/util/error.h"

namespace aaf {

void run_with_threads(int threads, const std::function<void()> &work) {
    if (threads < 0 || threads > kMaxThreads) throw Error("--threads must lie in [0, 1024]");
    // oneTBB caps its workers at the hardware's threads (and warns) unless
    // the process-wide limit is raised: raise it, so `threads` really run.
    std::optional<tbb::global_control> allow;
    if (threads > tbb::info::default_concurrency())
        allow.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
    arena.execute(work);
}

}  // namespace aaf
