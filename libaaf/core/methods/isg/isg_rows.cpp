// The per-pixel loops of isg-glossy and isg-dof (isg_rows.h) for every
// instruction set Google Highway targets, chosen at run time, and what every
// ISG sweep shares outside them; isg-shadow's are in isg_shadow_rows.cpp.
// Each lane is one pixel and computes what the scalar formulas
// (isg_formulas.h) compute, operation for operation; the range weights'
// exponential is exp2_nonpositive (vector_math-inl.h: plain multiplies and
// adds, the same bits on every instruction set).
#include "isg_rows.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

// Arrays of lanes need sized vector types: no scalable (SVE, RVV) targets.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/isg/isg_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "aaf/core/kernels/vector_math-inl.h"
#include "methods/isg/isg_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace aaf::isg {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// exp(-(a l^2 + b n^2) / sigma) (ISG Eq. 10-12) with n = 1 - N.N0, at
/// least 2^-64; NaN lanes are dropped from `m`.
HWY_INLINE VF glossy_range(const GlossySweep &s, VI index, const Point &p0, const Point &n0, MF &m) {
    const DF df;
    const Point delta = load_point(s.position, index) - p0;
    const VF n = hn::Sub(hn::Set(df, 1.0f), dot(load_point(s.normal, index), n0));
    // a l^2 from the squared distance (no square root), in base 2; a, b >= 0,
    // so the exponent is <= 0.
    const VF a_l2 =
        hn::Mul(dot(delta, delta), hn::Set(df, s.a * (s.range.inv_scene_size * s.range.inv_scene_size)));
    const VF b_n2 = hn::Mul(hn::Mul(hn::Set(df, s.b), n), n);
    const VF exponent = hn::Mul(hn::Add(a_l2, b_n2), hn::Set(df, -1.44269504f * s.range.inv_sigma));
    m = hn::AndNot(hn::IsNaN(exponent), m);
    return detail::HWY_NAMESPACE::exp2_nonpositive(df, exponent);
}

/// ISG Sec. 3.2's parameter search: the mean reflected distance within
/// theta_max's projection (infinity where no tap's ray hit anything).
HWY_INLINE VF glossy_search(const GlossySweep &s, const RowLanes &lanes, MF valid, const Point &p0,
                            const Point &n0, VF theta) {
    const DF df;
    const VF radius_px = clamp_radius(hn::Mul(theta, hn::Set(df, s.px_per_rad)), s.range.max_radius_px);
    WeightedSums<1> sums;
    for (int t = 0; t < s.search->count(); ++t) {
        const TapPixel tap = tap_pixel(s.layout, lanes.x, lanes.y, radius_px, s.search->x[t], s.search->y[t]);
        MF m = hn::And(valid, tap.inside);
        if (hn::AllFalse(df, m)) continue;
        const VF e_m = load(s.reflected_m, tap.index);
        m = hn::And(m, hn::And(hn::Gt(e_m, hn::Zero(df)), hn::IsFinite(e_m)));
        if (hn::AllFalse(df, m)) continue;
        const VF w = glossy_range(s, tap.index, p0, n0, m);
        sums.add(m, w, {e_m});
    }
    return hn::IfThenElse(sums.positive(), sums.mean(0), hn::Set(df, kInf));
}

/// ISG Eq. 13-14: the gather's radius, the angle alpha through std::atan and
/// std::tan (glossy_gather_angle()) lane by lane, as the scalar formula does.
HWY_INLINE VF glossy_gather_radius(const GlossySweep &s, const RowLanes &lanes, MF valid, const Point &p0,
                                   const Point &n0, VF theta, VF reflected_m) {
    const DF df;
    const Point to_eye = broadcast(s.eye) - p0;
    const VF eye_distance_m = length(to_eye);
    HWY_ALIGN float theta_rad[kMaxLanes], eye_m[kMaxLanes], reflected[kMaxLanes], alpha[kMaxLanes];
    hn::Store(theta, df, theta_rad);
    hn::Store(eye_distance_m, df, eye_m);
    hn::Store(reflected_m, df, reflected);
    hn::Store(hn::IfThenElseZero(valid, hn::Set(df, 1.0f)), df, alpha);  // 1 where valid
    for (int i = 0; i < lanes.count; ++i)
        if (alpha[i] != 0)
            alpha[i] = glossy_gather_angle(theta_rad[i], eye_m[i], reflected[i]);  // ISG Eq. 13
    const VF cos_incident = hn::Div(hn::Abs(dot(n0, to_eye)), eye_distance_m);
    const VF angle = hn::IfThenElseZero(valid, hn::Load(df, alpha));
    return clamp_radius(hn::Mul(hn::Mul(angle, hn::Set(df, s.px_per_rad)), cos_incident),
                        s.range.max_radius_px);  // ISG Eq. 14
}

HWY_INLINE void glossy_gather(const GlossySweep &s, const RowLanes &lanes, MF valid, const Point &p0,
                              const Point &n0, VF radius_px, VF (&out)[3]) {
    const DF df;
    WeightedSums<3> sums;
    for (int t = 0; t < s.gather->count(); ++t) {
        const TapPixel tap = tap_pixel(s.layout, lanes.x, lanes.y, radius_px, s.gather->x[t], s.gather->y[t]);
        MF m = hn::And(valid, tap.inside);
        if (hn::AllFalse(df, m)) continue;
        const VF c[3] = {load(s.reflection[0], tap.index), load(s.reflection[1], tap.index),
                         load(s.reflection[2], tap.index)};
        m = hn::And(m, all_finite({c[0], c[1], c[2]}));
        const VF w = hn::Mul(hn::Set(df, s.gather_spatial[t]), glossy_range(s, tap.index, p0, n0, m));
        sums.add(m, w, c);
    }
    const MF gathered = hn::And(valid, sums.positive());
    for (int c = 0; c < 3; ++c) out[c] = hn::IfThenElse(gathered, sums.mean(c), out[c]);
}

void GlossyRow(const GlossySweep &s, int y) {
    const DF df;
    for (int x0 = 0; x0 < s.layout.width; x0 += int(hn::Lanes(df))) {
        const RowLanes lanes = row_lanes(s.layout, x0, y);
        VF out[3] = {load_centre(s.reflection[0], lanes), load_centre(s.reflection[1], lanes),
                     load_centre(s.reflection[2], lanes)};
        const VF theta = load_centre(s.theta_max, lanes);
        const Point p0 = load_centre_point(s.position, lanes), n0 = load_centre_point(s.normal, lanes);
        const MF valid =
            hn::And(hn::And(lanes.in_row, hn::And(hn::Gt(theta, hn::Zero(df)), hn::IsFinite(theta))),
                    hn::And(all_finite(p0), all_finite(n0)));
        if (!hn::AllFalse(df, valid)) {
            const VF reflected_m = glossy_search(s, lanes, valid, p0, n0, theta);
            const VF radius_px = glossy_gather_radius(s, lanes, valid, p0, n0, theta, reflected_m);
            glossy_gather(s, lanes, valid, p0, n0, radius_px, out);
        }
        for (int c = 0; c < 3; ++c) store(out[c], s.out[c], lanes);
    }
}

/// isg-dof's depth: 0 is the background at infinity, a non-finite or
/// negative depth unknown (NaN).
HWY_INLINE VF dof_depth_value(VF z) {
    const DF df;
    const VF known = hn::IfThenElse(hn::And(hn::IsFinite(z), hn::Gt(z, hn::Zero(df))), z, hn::Set(df, NAN));
    return hn::IfThenElse(hn::Eq(z, hn::Zero(df)), hn::Set(df, kInf), known);
}

HWY_INLINE VF dof_depth(const DofSweep &s, VI index) {
    return dof_depth_value(load(s.depth_m, index));
}

/// circle_of_confusion_px() (ISG Eq. 15) of depths from dof_depth().
HWY_INLINE VF circle_of_confusion_px(const DofSweep &s, VF z) {
    const DF df;
    const VF c_inf = hn::Set(df, s.coc_inf_px);
    const VF finite = hn::Mul(hn::Div(hn::Abs(hn::Sub(z, hn::Set(df, s.focus_m))), z), c_inf);
    return hn::IfThenElse(hn::IsInf(z), c_inf, finite);
}

/// relative_depth_behind() of isg_dof_method.cpp: (z - z0) / z0, the background at +inf.
HWY_INLINE VF relative_depth_behind(VF z, VF z0) {
    const DF df;
    const VF inf = hn::Set(df, kInf);
    const VF from_background = hn::IfThenElseZero(hn::Not(hn::IsInf(z)), hn::Neg(inf));
    const VF finite = hn::IfThenElse(hn::IsInf(z), inf, hn::Div(hn::Sub(z, z0), z0));
    return hn::IfThenElse(hn::IsInf(z0), from_background, finite);
}

/// smoothstep() of isg_formulas.h: Min and Max in the argument order of
/// std::min(1, .) and std::max(0, .), which keep their bits.
HWY_INLINE VF smoothstep(float width, VF x) {
    const DF df;
    const VF one = hn::Set(df, 1.0f);
    if (!(width > 0)) return hn::IfThenElseZero(hn::Gt(x, hn::Zero(df)), one);
    const VF t = hn::Min(hn::Max(hn::Div(x, hn::Set(df, width)), hn::Zero(df)), one);
    return hn::Mul(hn::Mul(t, t), hn::Sub(hn::Set(df, 3.0f), hn::Mul(hn::Set(df, 2.0f), t)));
}

/// c_inf + s (c_i - c_inf), s the smoothed depth test where `closer` holds (ISG Eq. 16-17).
HWY_INLINE VF dof_weight(const DofSweep &s, MF closer, VF relative_depth, VF ci) {
    const DF df;
    const VF c_inf = hn::Set(df, s.coc_inf_px);
    const VF test = hn::IfThenElseZero(closer, smoothstep(s.transition, relative_depth));
    return hn::Add(c_inf, hn::Mul(test, hn::Sub(ci, c_inf)));
}

/// ISG Sec. 3.3's parameter search within c_inf: the mean circle of
/// confusion weighted after ISG Eq. 16. Its radius is the same for every
/// pixel, so are its taps' offsets (`dx`, `dy`).
HWY_INLINE MF dof_search(const DofSweep &s, const RowLanes &lanes, MF valid, VF z0, VF c0, const int *dx,
                         const int *dy, VF &radius_px) {
    const DI di;
    WeightedSums<1> sums;
    for (int t = 0; t < s.search->count(); ++t) {
        const TapPixel tap = tap_pixel(s.layout, lanes.x, lanes.y, hn::Set(di, dx[t]), hn::Set(di, dy[t]));
        MF m = hn::And(valid, tap.inside);
        const VF zi = dof_depth(s, tap.index);
        m = hn::AndNot(hn::IsNaN(zi), m);
        const VF ci = circle_of_confusion_px(s, zi);
        const VF w = dof_weight(s, hn::Gt(ci, c0), relative_depth_behind(zi, z0), ci);  // ISG Eq. 16
        sums.add(m, w, {ci});
    }
    radius_px = clamp_radius(sums.mean(0), s.max_radius_px);
    return hn::And(valid, sums.positive());
}

/// The gather of ISG Eq. 4 with ISG Eq. 17's weights.
HWY_INLINE void dof_gather(const DofSweep &s, const RowLanes &lanes, MF found, VF z0, VF c0, VF radius_px,
                           VF (&out)[3]) {
    const DF df;
    WeightedSums<3> sums;
    for (int t = 0; t < s.gather->count(); ++t) {
        const TapPixel tap = tap_pixel(s.layout, lanes.x, lanes.y, radius_px, s.gather->x[t], s.gather->y[t]);
        MF m = hn::And(found, tap.inside);
        if (hn::AllFalse(df, m)) continue;
        const VF zi = dof_depth(s, tap.index);
        const VF c[3] = {load(s.sharp[0], tap.index), load(s.sharp[1], tap.index),
                         load(s.sharp[2], tap.index)};
        m = hn::And(hn::AndNot(hn::IsNaN(zi), m), all_finite({c[0], c[1], c[2]}));
        const VF ci = circle_of_confusion_px(s, zi);
        const VF w = dof_weight(s, hn::Lt(ci, c0), hn::Neg(relative_depth_behind(zi, z0)), ci);  // ISG Eq. 17
        sums.add(m, w, c);
    }
    const MF gathered = hn::And(found, sums.positive());
    for (int c = 0; c < 3; ++c) out[c] = hn::IfThenElse(gathered, sums.mean(c), out[c]);
}

void DofRow(const DofSweep &s, int y) {
    const DF df;
    // The search radius is c_inf for every pixel: its tap offsets once per row.
    const float search_px = s.coc_inf_px > 0 ? std::min(s.coc_inf_px, s.max_radius_px) : 0.0f;
    std::vector<int> dx(std::size_t(s.search->count())), dy(dx.size());
    for (std::size_t t = 0; t < dx.size(); ++t) {
        dx[t] = int(std::lround(s.search->x[t] * search_px));
        dy[t] = int(std::lround(s.search->y[t] * search_px));
    }
    for (int x0 = 0; x0 < s.layout.width; x0 += int(hn::Lanes(df))) {
        const RowLanes lanes = row_lanes(s.layout, x0, y);
        VF out[3] = {load_centre(s.sharp[0], lanes), load_centre(s.sharp[1], lanes),
                     load_centre(s.sharp[2], lanes)};
        const VF z0 = dof_depth_value(load_centre(s.depth_m, lanes));
        const MF valid = hn::AndNot(hn::IsNaN(z0), lanes.in_row);
        if (s.coc_inf_px > 0 && !hn::AllFalse(df, valid)) {
            const VF c0 = circle_of_confusion_px(s, z0);
            VF radius_px;
            const MF found = dof_search(s, lanes, valid, z0, c0, dx.data(), dy.data(), radius_px);
            if (!hn::AllFalse(df, found)) dof_gather(s, lanes, found, z0, c0, radius_px, out);
        }
        for (int c = 0; c < 3; ++c) {
            store(out[c], s.out[c], lanes);
            store(out[c], s.beauty[c], lanes);
        }
    }
}

const char *RowsTarget() {
    return hwy::TargetName(HWY_TARGET);
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::isg
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <string>

#include "aaf/core/util/error.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/parallel.h"

namespace aaf::isg {

HWY_EXPORT(GlossyRow);
HWY_EXPORT(DofRow);
HWY_EXPORT(RowsTarget);

namespace {

bool shared_layout(const std::vector<ConstPlaneView> &views, PlaneLayout &layout) {
    if (views.empty()) return false;
    const ConstPlaneView &first = views.front();
    for (const ConstPlaneView &view : views)
        if (view.width != first.width || view.height != first.height || view.row_stride != first.row_stride ||
            view.pixel_stride != first.pixel_stride)
            return false;
    // Every index a sweep computes (a product and a sum of them, times 4
    // for the packed quadruples) fits an int.
    constexpr std::ptrdiff_t kMax = std::numeric_limits<int>::max() / 8;
    if (first.width < 1 || first.height < 1 || first.row_stride < 0 || first.pixel_stride < 0 ||
        std::ptrdiff_t(first.height) * first.row_stride > kMax ||
        std::ptrdiff_t(first.width) * first.pixel_stride > kMax)
        return false;
    layout = {first.width, first.height, int(first.row_stride), int(first.pixel_stride)};
    return true;
}

}  // namespace

SweepPlanes::SweepPlanes(const std::vector<ConstPlaneView> &views) {
    if (shared_layout(views, layout_)) {
        for (const ConstPlaneView &view : views) data_.push_back(view.data);
        return;
    }
    // Views of different layouts (or none fitting an int index): packed copies.
    const int width = views.front().width, height = views.front().height;
    if (std::ptrdiff_t(width) * height > std::numeric_limits<int>::max() / 8)
        throw Error("an image of " + std::to_string(width) + " x " + std::to_string(height) +
                    " pixels is too large for the ISG methods");
    layout_ = {width, height, width, 1};
    for (const ConstPlaneView &view : views) {
        std::vector<float> &copy = copies_.emplace_back(std::size_t(width) * std::size_t(height));
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                copy[std::size_t(y) * std::size_t(width) + std::size_t(x)] = view(x, y);
        data_.push_back(copy.data());
    }
}

TapArrays::TapArrays(const std::vector<Tap> &taps) {
    for (const Tap &tap : taps) {
        x.push_back(tap.x);
        y.push_back(tap.y);
        max_abs_x = std::max(max_abs_x, std::abs(tap.x));
        max_abs_y = std::max(max_abs_y, std::abs(tap.y));
    }
}

void glossy_row(const GlossySweep &sweep, int y) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(GlossyRow)(sweep, y);
}

void dof_row(const DofSweep &sweep, int y) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(DofRow)(sweep, y);
}

const char *rows_target() {
    (void)instruction_set();
    return HWY_DYNAMIC_DISPATCH(RowsTarget)();
}

}  // namespace aaf::isg
#endif  // HWY_ONCE
