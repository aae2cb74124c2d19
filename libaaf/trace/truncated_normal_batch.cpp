// TruncatedNormal's cubic inverse CDF over a batch (truncated_normal_batch.h)
// for every instruction set Google Highway targets, chosen at run time.
#include "truncated_normal_batch.h"

// As libaaf/core/kernels/gather_rows.cpp: no scalable (SVE, RVV) targets.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "truncated_normal_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace aaf::trace::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// One value as TruncatedNormal::sample() computes it (the vector loop's tail).
float SampleOne(const float *cubics, int intervals, float limit, float v) {
    if (!(v > 0)) return -limit;
    if (v >= 1) return limit;
    const float position = v * float(intervals);
    const int i = int(position) < intervals - 1 ? int(position) : intervals - 1;
    const float t = position - float(i);
    const float *c = cubics + 4 * i;
    const float next_x0 = c[4];
    const float x = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
    return x < c[0] ? c[0] : (next_x0 < x ? next_x0 : x);  // std::clamp(x, x0, next_x0)
}

/// Lanes are consecutive values; each lane gathers its interval's cubic.
void SampleCubicBatch(const float *cubics, int intervals, float limit, const float *u, std::size_t count,
                      float scale, float *out) {
    const hn::ScalableTag<float> df;
    const hn::RebindToSigned<decltype(df)> di;
    const std::size_t lanes = hn::Lanes(df);
    const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f);
    const auto low = hn::Set(df, -limit), high = hn::Set(df, limit), scale_v = hn::Set(df, scale);
    const auto n = hn::Set(df, float(intervals));
    const auto last = hn::Set(di, intervals - 1), first = hn::Zero(di);
    std::size_t k = 0;
    for (; k + lanes <= count; k += lanes) {
        const auto v = hn::LoadU(df, u + k);
        const auto position = hn::Mul(v, n);
        // Truncation, as int(position); out-of-range lanes (u outside (0, 1))
        // are clamped only to keep the gathers inside the table.
        const auto i = hn::Min(hn::Max(hn::ConvertTo(di, position), first), last);
        const auto t = hn::Sub(position, hn::ConvertTo(df, i));
        const auto base = hn::ShiftLeft<2>(i);  // 4 floats per interval
        const auto x0 = hn::GatherIndex(df, cubics, base);
        const auto slope0 = hn::GatherIndex(df, cubics + 1, base);
        const auto c2 = hn::GatherIndex(df, cubics + 2, base);
        const auto c3 = hn::GatherIndex(df, cubics + 3, base);
        const auto next_x0 = hn::GatherIndex(df, cubics + 4, base);
        const auto x = hn::Add(x0, hn::Mul(t, hn::Add(slope0, hn::Mul(t, hn::Add(c2, hn::Mul(t, c3))))));
        // std::clamp(x, x0, next_x0), comparison for comparison (signed zeros included).
        const auto clamped =
            hn::IfThenElse(hn::Lt(x, x0), x0, hn::IfThenElse(hn::Lt(next_x0, x), next_x0, x));
        const auto sampled =
            hn::IfThenElse(hn::Not(hn::Gt(v, zero)), low, hn::IfThenElse(hn::Ge(v, one), high, clamped));
        hn::StoreU(hn::Mul(scale_v, sampled), df, out + k);
    }
    for (; k < count; ++k) out[k] = scale * SampleOne(cubics, intervals, limit, u[k]);
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::trace::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::trace::detail {

HWY_EXPORT(SampleCubicBatch);

void sample_cubic_batch(const float *cubics, int intervals, float limit, const float *u, std::size_t count,
                        float scale, float *out) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(SampleCubicBatch)(cubics, intervals, limit, u, count, scale, out);
}

}  // namespace aaf::trace::detail
#endif
