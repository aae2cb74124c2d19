#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

#include "aaf/core/util/error.h"

namespace aaf::io {

/// Throws aaf::InputError unless `channels` float planes of width x height
/// fit `budget_bytes`: checked from the header, before any allocation.
inline void check_memory_budget(const std::string &path, std::int64_t width, std::int64_t height,
                                std::int64_t channels, std::uint64_t budget_bytes) {
    const double bytes = double(std::max<std::int64_t>(width, 0)) *
                         double(std::max<std::int64_t>(height, 0)) * double(channels) * 4;
    const double budget = double(budget_bytes);
    if (bytes <= budget) return;
    char sizes[96];
    std::snprintf(sizes, sizeof sizes, "(%.3g GiB), over the memory limit of %.3g GiB",
                  bytes / double(1 << 30), budget / double(1 << 30));
    throw InputError(path + ": declares " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                     std::to_string(channels) + " channels " + sizes +
                     " (raise with --memory-limit-gb or AAF_MEMORY_LIMIT_GB)");
}

}  // namespace aaf::io
