#pragma once

#include <functional>

namespace aaf {

/// The most worker threads a command may ask for.
inline constexpr int kMaxThreads = 1024;

/// Runs `work` on `threads` oneTBB workers (0 = all hardware threads) and
/// returns when it is done. Results never depend on the count; only the
/// speed does; more threads than cores still run (no oneTBB warning).
/// Throws aaf::Error "--threads must lie in [0, 1024]" (every command
/// spells the option so) for a count outside [0, kMaxThreads].
void run_with_threads(int threads, const std::function<void()> &work);

}  // namespace aaf
