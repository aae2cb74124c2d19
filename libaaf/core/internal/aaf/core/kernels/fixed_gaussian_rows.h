#pragma once

namespace aaf::detail {

/// sum[x] = the sum over t = 0, 1, ..., taps - 1, in that order from 0, of
/// weights[t] * double(rows[t][x]), for x in [0, count): every tap of the
/// fixed Gaussian (fixed_gaussian.h) over a row of centres, in the widest
/// double vectors the CPU has (Google Highway, chosen at run time), each
/// centre's sum in a register, each multiply and add rounded on its own, so
/// every instruction set gives the bits of the scalar loop.
void gaussian_taps(const float *const *rows, const double *weights, int taps, double *sum, int count);

}  // namespace aaf::detail
