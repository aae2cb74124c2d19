// The fixed Gaussian's taps over a row (fixed_gaussian_rows.h) for every
// instruction set Google Highway targets, chosen at run time. Compiled
// without contraction (CMakeLists.txt): no multiply-add is fused, so the
// sums are those of the scalar definition on every instruction set.
#include "aaf/core/kernels/fixed_gaussian_rows.h"

#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kernels/fixed_gaussian_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void GaussianTaps(const float *const *HWY_RESTRICT rows, const double *HWY_RESTRICT weights, int taps,
                  double *HWY_RESTRICT sum, int count) {
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;
    const int lanes = int(hn::Lanes(dd));
    int x = 0;
    // A vector of centres at a time, its sums in a register over all the taps.
    for (; x + lanes <= count; x += lanes) {
        auto total = hn::Zero(dd);
        for (int t = 0; t < taps; ++t)
            total = hn::Add(total,
                            hn::Mul(hn::Set(dd, weights[t]), hn::PromoteTo(dd, hn::LoadU(df, rows[t] + x))));
        hn::StoreU(total, dd, sum + x);
    }
    for (; x < count; ++x) {
        double total = 0;
        for (int t = 0; t < taps; ++t) total += weights[t] * double(rows[t][x]);
        sum[x] = total;
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(GaussianTaps);

void gaussian_taps(const float *const *rows, const double *weights, int taps, double *sum, int count) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(GaussianTaps)(rows, weights, taps, sum, count);
}

}  // namespace aaf::detail
#endif
