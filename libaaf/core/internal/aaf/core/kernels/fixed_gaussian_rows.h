#pragma once

namespace aaf::detail {

/// sum[x] += weight * double(row[x]) for x in [0, count): one tap of the
/// fixed Gaussian (fixed_gaussian.h) over a row of centres, in the widest
/// double vectors the CPU has (Google Highway, chosen at run time), each
/// multiply and add rounded on its own, so every instruction set gives the
/// bits of the scalar loop.
void gaussian_tap_row(double *sum, const float *row, double weight, int count);

}  // namespace aaf::detail
