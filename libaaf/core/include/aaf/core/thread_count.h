#pragma once

#include <functional>

namespace aaf {

/// Runs `work` on `threads` oneTBB workers (0 = all hardware threads) and
/// returns when it is done. Results never depend on the count; only the
/// speed does. Throws aaf::Error "--threads must be >= 0" (every command
/// spells the option so) for a negative count.
void run_with_threads(int threads, const std::function<void()> &work);

}  // namespace aaf
