#pragma once

#include <cstddef>

namespace aaf::trace::detail {

/// out[k] = scale * x(u[k]) for k < count, where x is TruncatedNormal's
/// cubic inverse CDF (`cubics`: x0, slope0, c2, c3 per interval for
/// `intervals` intervals, then a sentinel whose x0 is the limit), -limit for
/// u <= 0 or NaN and limit for u >= 1. The same operations in the same order
/// as TruncatedNormal::sample() with no interval on the exact inverse, so the
/// same bits, vectorised for the instruction set found at run time (Google
/// Highway; no fused multiply-adds).
void sample_cubic_batch(const float *cubics, int intervals, float limit, const float *u, std::size_t count,
                        float scale, float *out);

}  // namespace aaf::trace::detail
