#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "random.h"

namespace aaf::trace {

/// A point of the unit square [0, 1)^2.
struct UnitPoint {
    float s = 0, t = 0;
};

/// Jittered stratification of `count` samples of the unit square: a grid of
/// ceil(sqrt(count)) columns and ceil(count / columns) rows, one sample per
/// stratum. A perfect square (9 -> 3x3) fills the grid; otherwise the grid
/// has up to columns - 1 strata to spare, and a per-pixel key picks which
/// `count` strata get a sample through a hashed permutation (random.h), so no
/// part of the square is systematically left out.
class StratifiedGrid {
  public:
    /// `count` >= 1 samples.
    explicit StratifiedGrid(std::uint32_t count)
        : count_(count),
          columns_(std::max(1u, std::uint32_t(std::ceil(std::sqrt(double(count)))))),
          rows_((count + columns_ - 1) / columns_),
          inv_columns_(1.0f / float(columns_)),
          inv_rows_(1.0f / float(rows_)) {}

    std::uint32_t count() const { return count_; }
    std::uint32_t columns() const { return columns_; }
    std::uint32_t rows() const { return rows_; }

    /// Sample `index` (< count) of a pixel: its stratum, chosen by `key`
    /// when the grid has spare strata, jittered by (u1, u2) in [0, 1)^2.
    UnitPoint point(std::uint32_t index, std::uint32_t key, float u1, float u2) const {
        const std::uint32_t strata = columns_ * rows_;
        const std::uint32_t stratum = count_ == strata ? index : permute_index(index, strata, key);
        // The minimum guards the float rounding of (k + u) / n up to 1.
        constexpr float kBelowOne = 0x1.fffffep-1f;
        const std::uint32_t row = row_of(stratum), column = stratum - row * columns_;
        return {std::min((float(column) + u1) * inv_columns_, kBelowOne),
                std::min((float(row) + u2) * inv_rows_, kBelowOne)};
    }

    /// stratum / columns without an integer division (the hot loop's slowest
    /// instruction): (s + 1/2) / c lies at least 1/(2c) from an integer, far
    /// beyond float's rounding for the counts allowed (s < 2^20, c <= 1024),
    /// so the floor is exact.
    std::uint32_t row_of(std::uint32_t stratum) const {
        return std::uint32_t((float(stratum) + 0.5f) * inv_columns_);
    }

  private:
    std::uint32_t count_, columns_, rows_;
    float inv_columns_, inv_rows_;  ///< multiplications instead of divisions in the hot loop
};

}  // namespace aaf::trace
