#pragma once

#include <string>
#include <vector>

#include "aaf/core/aov_set.h"

namespace aaf {

/// Error of a test image against a reference over a set of channels.
struct ErrorMetrics {
    double mse = 0;           ///< mean over pixels and channels of (test - ref)^2
    double rmse = 0;          ///< sqrt(mse)
    double psnr = 0;          ///< 10 log10(peak^2 / mse) dB with peak = 1; +inf when equal
    std::size_t samples = 0;  ///< pixels x channels compared
};

/// Compares `channels` of `test` against the same channels of `reference`.
/// Throws aaf::Error on a size mismatch, a missing channel, or a non-finite
/// value (naming the channel and pixel).
ErrorMetrics compare_channels(const AovSet &test, const AovSet &reference,
                              const std::vector<std::string> &channels);

}  // namespace aaf
