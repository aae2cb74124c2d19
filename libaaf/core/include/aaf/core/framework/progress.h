#pragma once

#include <functional>

#include "aaf/core/util/error.h"

namespace aaf {

/// Called with the fraction of the work done, in [0, 1] and never
/// decreasing; returning false asks the computation to stop (as Open Image
/// Denoise's progress monitor).
using ProgressMonitor = std::function<bool(double fraction_done)>;

/// Thrown when a ProgressMonitor asked a computation to stop; nothing it
/// would have produced was returned.
class Cancelled : public Error {
  public:
    Cancelled() : Error("cancelled") {}
};

/// Reports a computation's progress to an optional monitor, from the calling
/// thread only, between stages of the work.
class Progress {
  public:
    explicit Progress(ProgressMonitor monitor = {}) : monitor_(std::move(monitor)) {}

    /// Reports `fraction_done` (clamped to [0, 1] and to at least the last
    /// value reported). Throws Cancelled when the monitor returns false.
    void report(double fraction_done);

  private:
    ProgressMonitor monitor_;
    double last_ = 0;
};

}  // namespace aaf
