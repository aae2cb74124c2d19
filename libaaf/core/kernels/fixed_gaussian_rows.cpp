// The fixed Gaussian's tap loop (fixed_gaussian_rows.h) for every
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

void GaussianTapRow(double *HWY_RESTRICT sum, const float *HWY_RESTRICT row, double weight, int count) {
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;  // as many floats as doubles
    const auto w = hn::Set(dd, weight);
    const int lanes = int(hn::Lanes(dd));
    int x = 0;
    for (; x + lanes <= count; x += lanes) {
        const auto tap = hn::Mul(w, hn::PromoteTo(dd, hn::LoadU(df, row + x)));
        hn::StoreU(hn::Add(hn::LoadU(dd, sum + x), tap), dd, sum + x);
    }
    for (; x < count; ++x) sum[x] += weight * double(row[x]);
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(GaussianTapRow);

void gaussian_tap_row(double *sum, const float *row, double weight, int count) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(GaussianTapRow)(sum, row, weight, count);
}

}  // namespace aaf::detail
#endif
