// The occluder fill's search (occluder_fill_rows.h) for every instruction set
// Google Highway targets, chosen at run time.
#include "aaf/core/methods/aaf/occluder_fill_rows.h"

#include <cstdlib>

// As gather_rows.cpp: no scalable (SVE, RVV) targets.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/aaf/occluder_fill_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Neighbouring centres in the lanes, each its own float sums over the same
/// disc offsets in the window's reading order: a lane adds exactly the taps
/// the scalar loop would, one at a time.
void SearchOccluderRow(const OccluderSearch &s, int y, const float *centre_id, float *out_d2_min_m,
                       float *out_d2_max_m) {
    const hn::ScalableTag<float> df;
    constexpr int kMaxLanes = int(HWY_LANES(float));
    static_assert(kMaxLanes <= kOccluderSearchPadding, "the padding covers a vector");
    const int lanes = int(hn::Lanes(df));
    const int r = s.pad;
    const int y_begin = y - r < 0 ? 0 : y - r, y_end = y + r > s.height - 1 ? s.height - 1 : y + r;
    for (int x0 = 0; x0 < s.width; x0 += lanes) {
        const auto centre = hn::LoadU(df, centre_id + x0);
        const auto searching = hn::Eq(centre, centre);  // NaN: no search
        if (hn::AllFalse(df, searching)) continue;
        auto sum_min = hn::Zero(df), sum_max = hn::Zero(df), lenders = hn::Zero(df);
        const auto one = hn::Set(df, 1.0f);
        for (int ny = y_begin; ny <= y_end; ++ny) {
            // No occluded pixel within pad columns of any centre: the row adds nothing.
            const unsigned char *const near =
                s.occluded_near + std::size_t(ny - s.first_row) * s.near_stride + std::size_t(x0);
            bool any_near = false;
            for (int l = 0; l < lanes; ++l) any_near |= near[l] != 0;
            if (!any_near) continue;
            const int w = s.half_width[std::abs(ny - y)];
            const std::size_t row = std::size_t(ny - s.first_row) * s.padded_width + std::size_t(r + x0);
            for (int dx = -w; dx <= w; ++dx) {
                const std::size_t t = row + std::size_t(std::ptrdiff_t(dx));
                const auto lends = hn::Eq(hn::LoadU(df, s.lender_id + t), centre);  // NaN lends to none
                sum_min = hn::IfThenElse(lends, hn::Add(sum_min, hn::LoadU(df, s.d2_min_m + t)), sum_min);
                sum_max = hn::IfThenElse(lends, hn::Add(sum_max, hn::LoadU(df, s.d2_max_m + t)), sum_max);
                lenders = hn::IfThenElse(lends, hn::Add(lenders, one), lenders);
            }
        }
        alignas(64) float sums[3][kMaxLanes];
        hn::Store(sum_min, df, sums[0]);
        hn::Store(sum_max, df, sums[1]);
        hn::Store(lenders, df, sums[2]);
        for (int l = 0; l < lanes && x0 + l < s.width; ++l) {
            if (sums[2][l] == 0) continue;
            // The scalar loop's sum / count, count an exact small integer.
            out_d2_min_m[x0 + l] = sums[0][l] / sums[2][l];
            out_d2_max_m[x0 + l] = sums[1][l] / sums[2][l];
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(SearchOccluderRow);

void search_occluder_row(const OccluderSearch &search, int y, const float *centre_id, float *out_d2_min_m,
                         float *out_d2_max_m) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(SearchOccluderRow)(search, y, centre_id, out_d2_min_m, out_d2_max_m);
}

}  // namespace aaf::detail
#endif
