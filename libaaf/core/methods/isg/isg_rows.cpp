// The ISG methods' per-pixel loops (isg_rows.h) for every instruction set
// Google Highway targets, chosen at run time. Each lane is one pixel and
// computes what the scalar formulas (isg_formulas.h) compute, operation for
// operation; the range weights' exponential is exp2_nonpositive
// (vector_math-inl.h: plain multiplies and adds, the same bits on every
// instruction set).
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

HWY_BEFORE_NAMESPACE();
namespace aaf::isg {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A full vector of floats, one pixel per lane.
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;
constexpr int kMaxLanes = 16;  ///< as many floats as any fixed-size target's vector holds
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Point {
    VF x, y, z;
};

HWY_INLINE VF load(const float *plane, VI index) {
    return hn::GatherIndex(DF(), plane, index);
}

HWY_INLINE Point load_point(const float *const plane[3], VI index) {
    return {load(plane[0], index), load(plane[1], index), load(plane[2], index)};
}

/// Position and hard visibility of the lanes' pixels from quadruples
/// (x, y, z, V) at 4 x `index`: one 16-byte load per lane and a transpose
/// where a vector holds 4, 8 or 16 lanes (one cache line per tap, not four),
/// else four gathers.
template <class D>
HWY_INLINE void load_quadruples(D df, const float *packed, hn::Vec<hn::Rebind<int32_t, D>> index, Point &p,
                                hn::Vec<D> &v) {
    const auto at4 = hn::ShiftLeft<2>(index);
#if HWY_TARGET != HWY_SCALAR
    using V = hn::Vec<D>;
    constexpr std::size_t kLanes = hn::MaxLanes(D());
    if constexpr (kLanes == 4 || kLanes == 8 || kLanes == 16) {
        HWY_ALIGN int32_t at[kMaxLanes];
        hn::Store(at4, hn::Rebind<int32_t, D>(), at);
        const hn::Full128<float> d4;
        V q[4];
        for (int i = 0; i < 4; ++i) {
            if constexpr (kLanes == 4) {
                q[i] = hn::LoadU(d4, packed + at[i]);
            } else if constexpr (kLanes == 8) {
                q[i] = hn::Combine(df, hn::LoadU(d4, packed + at[i + 4]), hn::LoadU(d4, packed + at[i]));
            } else {
                const hn::Half<D> d8;
                q[i] = hn::Combine(
                    df,
                    hn::Combine(d8, hn::LoadU(d4, packed + at[i + 12]), hn::LoadU(d4, packed + at[i + 8])),
                    hn::Combine(d8, hn::LoadU(d4, packed + at[i + 4]), hn::LoadU(d4, packed + at[i])));
            }
        }
        // Per 128-bit block: (x0 x1 y0 y1), (x2 x3 y2 y3), (z0 z1 V0 V1), (z2 z3 V2 V3).
        const hn::Repartition<double, D> d64;
        const auto t0 = hn::BitCast(d64, hn::InterleaveLower(df, q[0], q[1]));
        const auto t1 = hn::BitCast(d64, hn::InterleaveLower(df, q[2], q[3]));
        const auto t2 = hn::BitCast(d64, hn::InterleaveUpper(df, q[0], q[1]));
        const auto t3 = hn::BitCast(d64, hn::InterleaveUpper(df, q[2], q[3]));
        p.x = hn::BitCast(df, hn::InterleaveLower(d64, t0, t1));
        p.y = hn::BitCast(df, hn::InterleaveUpper(d64, t0, t1));
        p.z = hn::BitCast(df, hn::InterleaveLower(d64, t2, t3));
        v = hn::BitCast(df, hn::InterleaveUpper(d64, t2, t3));
        return;
    }
#endif
    {
        p = {hn::GatherIndex(df, packed, at4), hn::GatherIndex(df, packed + 1, at4),
             hn::GatherIndex(df, packed + 2, at4)};
        v = hn::GatherIndex(df, packed + 3, at4);
    }
}

HWY_INLINE MF all_finite(const Point &p) {
    return hn::And(hn::IsFinite(p.x), hn::And(hn::IsFinite(p.y), hn::IsFinite(p.z)));
}

/// dot() of vec3.h: (a.x b.x + a.y b.y) + a.z b.z, each product rounded.
HWY_INLINE VF dot(const Point &a, const Point &b) {
    return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z));
}

HWY_INLINE VF length(const Point &v) {
    return hn::Sqrt(dot(v, v));
}

HWY_INLINE Point operator-(const Point &a, const Point &b) {
    return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)};
}

HWY_INLINE Point broadcast(Vec3 v) {
    const DF df;
    return {hn::Set(df, v.x), hn::Set(df, v.y), hn::Set(df, v.z)};
}

/// Every search and gather radius: r > 0 ? min(r, max) : 0, NaN to 0.
HWY_INLINE VF clamp_radius(VF radius_px, float max_radius_px) {
    const DF df;
    return hn::IfThenElseZero(hn::Gt(radius_px, hn::Zero(df)),
                              hn::Min(radius_px, hn::Set(df, max_radius_px)));
}

/// std::lround(t): the nearest integer, halves away from zero (|t| < 2^23):
/// t plus the float just below 1/2, signed as t, truncated (for every such
/// float, checked exhaustively: the sum rounds up to the next integer
/// exactly when t's fraction is at least 1/2).
HWY_INLINE VI round_half_away(VF t) {
    const DF df;
    return hn::ConvertTo(DI(), hn::Add(t, hn::CopySign(hn::Set(df, 0.49999997f), t)));
}

/// round_half_away(tap r) for a radius r >= 0 with |tap r| < 2^22: t has
/// the sign of the tap (or is a zero, which truncates to 0 with either
/// sign's half), so the signed half is a constant, and the integer's bits
/// come from the 1.5 * 2^23 shift (no range fix-up of a conversion).
HWY_INLINE VI round_half_away(float tap, VF radius) {
    const DF df;
    const VF rounded =
        hn::Trunc(hn::Add(hn::Mul(hn::Set(df, tap), radius), hn::Set(df, std::copysign(0.49999997f, tap))));
    return hn::Sub(hn::BitCast(DI(), hn::Add(rounded, hn::Set(df, 12582912.0f))), hn::Set(DI(), 0x4B400000));
}

/// Index of pixel (x, y) in every plane of `layout`.
HWY_INLINE VI pixel_index(const PlaneLayout &layout, VI x, VI y) {
    const DI di;
    return hn::Add(hn::Mul(y, hn::Set(di, layout.row_stride)), hn::Mul(x, hn::Set(di, layout.pixel_stride)));
}

/// Nearest-pixel point sampling: the pixel a tap falls in, (x, y) plus the
/// tap's offset times the radius rounded, for every lane: its index,
/// clamped to the image so that the load is safe, and whether it is inside
/// (a tap outside the image is passed over).
struct TapPixel {
    VI index;
    MF inside;
};

HWY_INLINE TapPixel tap_pixel(const PlaneLayout &layout, VI x, VI y, VI dx, VI dy) {
    const DI di;
    const VI sx = hn::Add(x, dx), sy = hn::Add(y, dy);
    const auto inside_x = hn::And(hn::Gt(sx, hn::Set(di, -1)), hn::Lt(sx, hn::Set(di, layout.width)));
    const auto inside_y = hn::And(hn::Gt(sy, hn::Set(di, -1)), hn::Lt(sy, hn::Set(di, layout.height)));
    const VI cx = hn::Min(hn::Max(sx, hn::Zero(di)), hn::Set(di, layout.width - 1));
    const VI cy = hn::Min(hn::Max(sy, hn::Zero(di)), hn::Set(di, layout.height - 1));
    return {pixel_index(layout, cx, cy), hn::RebindMask(DF(), hn::And(inside_x, inside_y))};
}

HWY_INLINE TapPixel tap_pixel(const PlaneLayout &layout, VI x, VI y, VF radius_px, float tap_x, float tap_y) {
    const DF df;
    return tap_pixel(layout, x, y, round_half_away(hn::Mul(hn::Set(df, tap_x), radius_px)),
                     round_half_away(hn::Mul(hn::Set(df, tap_y), radius_px)));
}

/// The lanes' pixels of row `y` from `x0` on, the last one repeated past the row's end.
struct RowLanes {
    VI x, y, centre;
    MF in_row;
    int count;
    std::ptrdiff_t first = -1;  ///< index of the first pixel when the lanes' pixels are consecutive, else -1
};

HWY_INLINE RowLanes row_lanes(const PlaneLayout &layout, int x0, int y) {
    const DI di;
    const VI x = hn::Iota(di, x0), row = hn::Set(di, y);
    const int count = std::min(int(hn::Lanes(di)), layout.width - x0);
    const bool consecutive = layout.pixel_stride == 1 && count == int(hn::Lanes(di));
    return {x,
            row,
            pixel_index(layout, hn::Min(x, hn::Set(di, layout.width - 1)), row),
            hn::FirstN(DF(), std::size_t(count)),
            count,
            consecutive ? std::ptrdiff_t(y) * layout.row_stride + x0 : -1};
}

/// A plane's values at the lanes' own pixels: one load where they are consecutive.
HWY_INLINE VF load_centre(const float *plane, const RowLanes &lanes) {
    return lanes.first >= 0 ? hn::LoadU(DF(), plane + lanes.first) : load(plane, lanes.centre);
}

HWY_INLINE Point load_centre_point(const float *const plane[3], const RowLanes &lanes) {
    return {load_centre(plane[0], lanes), load_centre(plane[1], lanes), load_centre(plane[2], lanes)};
}

HWY_INLINE void store(VF value, const PlaneView &out, const RowLanes &lanes) {
    const int x0 = hn::GetLane(lanes.x);
    if (out.pixel_stride == 1 && lanes.count == int(hn::Lanes(DF()))) {
        hn::StoreU(value, DF(), &out(x0, hn::GetLane(lanes.y)));
        return;
    }
    HWY_ALIGN float values[kMaxLanes];
    hn::Store(value, DF(), values);
    for (int i = 0; i < lanes.count; ++i) out(x0 + i, hn::GetLane(lanes.y)) = values[i];
}

/// Sums of ISG Eq. 4: a pixel's weights and its weighted values, each lane
/// adding its taps in order (float: the same bits for any vector width).
template <int kValues>
struct WeightedSums {
    VF weight, value[kValues];
    WeightedSums() {
        weight = hn::Zero(DF());
        for (int k = 0; k < kValues; ++k) value[k] = hn::Zero(DF());
    }
    /// Adds weight `w` of the lanes in `m` (the others add 0, which leaves
    /// a sum's bits as they are): value k gets w * values[k].
    void add(MF m, VF w, const VF (&values)[kValues]) {
        const VF w_in = hn::IfThenElseZero(m, w);
        weight = hn::Add(weight, w_in);
        for (int k = 0; k < kValues; ++k)
            value[k] = hn::Add(value[k], hn::Mul(w_in, hn::IfThenElseZero(m, values[k])));
    }
    /// add() of finite `values`: the lanes not in `m` add weight 0 and
    /// 0 x value = +-0, which leaves every sum's bits as they are (a sum
    /// that starts at +0 and adds is never -0).
    void add_finite(MF m, VF w, const VF (&values)[kValues]) {
        const VF w_in = hn::IfThenElseZero(m, w);
        weight = hn::Add(weight, w_in);
        for (int k = 0; k < kValues; ++k) value[k] = hn::Add(value[k], hn::Mul(w_in, values[k]));
    }
    /// The lanes whose weights sum to more than 0.
    MF positive() const { return hn::Gt(weight, hn::Zero(DF())); }
    VF mean(int k) const { return hn::Div(value[k], weight); }
};

/// exp(-l^2 / sigma), l = |p - p0| / scene size (ISG Eq. 6-7), at least
/// 2^-64 (exp2_nonpositive()'s floor: a far tap still counts where no other
/// does, as the exponential's own tiny value did); NaN lanes are dropped
/// from `m` (a non-finite weight passes the tap over).
HWY_INLINE VF shadow_range(const ShadowSweep &s, const Point &p, const Point &p0, MF &m) {
    const DF df;
    // In base 2, from the squared distance with the constants folded: no square root per tap.
    const Point delta = p - p0;
    const float scale = -1.44269504f * (s.range.inv_scene_size * s.range.inv_scene_size) * s.range.inv_sigma;
    const VF exponent = hn::Mul(dot(delta, delta), hn::Set(df, scale));
    m = hn::AndNot(hn::IsNaN(exponent), m);
    return detail::HWY_NAMESPACE::exp2_nonpositive(df, exponent);
}

/// The lanes' pixels in the packed planes of ShadowScratch (dense, row
/// after row, layout `dense`): `base` their own indices.
struct ShadowBlock {
    RowLanes lanes;
    PlaneLayout dense;
    VI base;
};

/// The index in the packed planes of the lanes' taps at (tap_x, tap_y)
/// times `radius_px`; a tap outside the image is dropped from `m` (never
/// one of an interior block).
template <bool kInterior>
HWY_INLINE VI shadow_tap(const ShadowBlock &b, VF radius_px, float tap_x, float tap_y, MF &m) {
    const DI di;
    // radius_px is >= 0 and at most max_radius_px (clamp_radius()), |tap| <= 1.
    const VI dx = round_half_away(tap_x, radius_px), dy = round_half_away(tap_y, radius_px);
    if constexpr (kInterior) {
        return hn::Add(b.base, hn::Add(hn::Mul(dy, hn::Set(di, b.dense.width)), dx));
    } else {
        const TapPixel tap = tap_pixel(b.dense, b.lanes.x, b.lanes.y, dx, dy);
        m = hn::And(m, tap.inside);
        return tap.index;
    }
}

/// One tap of a vector of pixels, read: the lanes it counts for, its
/// packed point and value.
struct ShadowTap {
    MF m;
    Point p;
    VF value;
};

/// Tap `t` of `taps` scaled by `radius_px` for the lanes in `m`, read from
/// `packed` (the index is clamped, so the read is safe for every lane); for
/// the search (kSearch) only where the packed distance is >= 0: in shadow,
/// ISG Eq. 6's inShadow, with a valid distance.
template <bool kInterior, bool kSearch>
HWY_INLINE ShadowTap read_shadow_tap(const ShadowBlock &b, const float *packed, const TapArrays &taps, int t,
                                     VF radius_px, MF m) {
    const DF df;
    ShadowTap tap;
    const VI index = shadow_tap<kInterior>(b, radius_px, taps.x[t], taps.y[t], m);
    load_quadruples(df, packed, index, tap.p, tap.value);
    tap.m = kSearch ? hn::And(m, hn::Ge(tap.value, hn::Zero(df))) : m;
    return tap;
}

/// ISG Eq. 4's sums over `taps` for the lanes in `m`, with the range
/// weights of ISG Eq. 6-7. Taps go two at a time, so that one's weight (a
/// square root and an exponential, long in latency) overlaps the other's;
/// they are added in order. A pair with no lane to count is passed over; a tap with none in
/// a pair adds zeros, which leave the sums' bits as they are (add_finite()).
template <bool kInterior, bool kSearch>
HWY_INLINE WeightedSums<1> shadow_sums(const ShadowSweep &s, const ShadowBlock &b, const float *packed,
                                       const TapArrays &taps, VF radius_px, MF m, const Point &p0) {
    const DF df;
    WeightedSums<1> sums;
    const int count = taps.count();
    int t = 0;
    for (; t + 1 < count; t += 2) {
        ShadowTap first = read_shadow_tap<kInterior, kSearch>(b, packed, taps, t, radius_px, m);
        ShadowTap second = read_shadow_tap<kInterior, kSearch>(b, packed, taps, t + 1, radius_px, m);
        if (hn::AllFalse(df, hn::Or(first.m, second.m))) continue;
        const VF w_first = shadow_range(s, first.p, p0, first.m);
        const VF w_second = shadow_range(s, second.p, p0, second.m);
        sums.add_finite(first.m, w_first, {first.value});
        sums.add_finite(second.m, w_second, {second.value});
    }
    if (t < count) {
        ShadowTap last = read_shadow_tap<kInterior, kSearch>(b, packed, taps, t, radius_px, m);
        if (!hn::AllFalse(df, last.m)) {
            const VF w = shadow_range(s, last.p, p0, last.m);
            sums.add_finite(last.m, w, {last.value});
        }
    }
    return sums;
}

/// ISG Eq. 4-7: the mean occluder distance of the in-shadow taps within
/// `radius_px` (shadow_search_radius()); false lanes found none. The packed
/// occluder distance is negative where a tap is not in shadow (ISG Eq. 6's
/// inShadow) or has no valid distance.
template <bool kInterior>
HWY_INLINE MF shadow_search(const ShadowSweep &s, const ShadowBlock &b, MF valid, const Point &p0,
                            VF radius_px, VF &occluder_m) {
    const WeightedSums<1> sums = shadow_sums<kInterior, true>(s, b, s.scratch->position_occluder.data(),
                                                              *s.search, radius_px, valid, p0);
    occluder_m = sums.mean(0);
    return hn::And(valid, sums.positive());
}

/// The gather of ISG Eq. 4: the hard visibility within `radius_px`
/// (shadow_gather_radius()), for the lanes in `found`; else `hard0`. A tap
/// whose V is not finite has a NaN weight, which passes it over (PackShadowRow()).
template <bool kInterior>
HWY_INLINE VF shadow_gather(const ShadowSweep &s, const ShadowBlock &b, MF found, const Point &p0,
                            VF radius_px, VF hard0) {
    const WeightedSums<1> sums =
        shadow_sums<kInterior, false>(s, b, s.scratch->position_hard.data(), *s.gather, radius_px, found, p0);
    return hn::IfThenElse(hn::And(found, sums.positive()), sums.mean(0), hard0);
}

/// ISG Eq. 5: the search's radius, the light's size projected at the pixel's depth.
HWY_INLINE VF shadow_search_radius(const ShadowSweep &s, VF z_eye) {
    const DF df;
    return clamp_radius(hn::Mul(hn::Div(hn::Set(df, s.light_size_m), z_eye), hn::Set(df, s.focal_px)),
                        s.range.max_radius_px);
}

/// ISG Eq. 8-9: the gather's radius, the penumbra's width projected at the pixel's depth.
HWY_INLINE VF shadow_gather_radius(const ShadowSweep &s, const Point &p0, VF z_eye, VF occluder_m) {
    const DF df;
    const VF light_distance_m = length(broadcast(s.light_center) - p0);
    const VF gap_m = hn::Sub(light_distance_m, occluder_m);
    const VF penumbra_m = hn::IfThenElse(hn::Gt(gap_m, hn::Zero(df)),
                                         hn::Div(hn::Mul(hn::Set(df, s.light_size_m), occluder_m), gap_m),
                                         hn::Set(df, kInf));  // ISG Eq. 8
    return clamp_radius(hn::Mul(hn::Div(penumbra_m, z_eye), hn::Set(df, s.focal_px)),
                        s.range.max_radius_px);  // ISG Eq. 9
}

/// The pixels the taps of the lanes can reach, `taps` scaled by radii up to
/// the largest of `radius_px` (a tap's offset rounds |t| r to at most
/// ceil(max |t| max r); one pixel more for safety).
struct Window {
    int x_lo, x_hi, y_lo, y_hi;
};

HWY_INLINE Window tap_window(const RowLanes &lanes, const TapArrays &taps, VF radius_px) {
    const DF df;
    const float r = hn::GetLane(hn::MaxOfLanes(df, radius_px));
    const int reach_x = int(std::ceil(taps.max_abs_x * r)) + 1,
              reach_y = int(std::ceil(taps.max_abs_y * r)) + 1;
    const int x0 = hn::GetLane(lanes.x), y = hn::GetLane(lanes.y);
    return {x0 - reach_x, x0 + int(hn::Lanes(df)) - 1 + reach_x, y - reach_y, y + reach_y};
}

/// Whether every tap of the window is inside the image (and the lanes fill a vector).
HWY_INLINE bool interior(const ShadowBlock &b, const Window &window) {
    return b.lanes.count == int(hn::Lanes(DF())) && window.x_lo >= 0 && window.y_lo >= 0 &&
           window.x_hi < b.dense.width && window.y_hi < b.dense.height;
}

/// How many tiles of `window` (clipped to the image) `table` of ShadowTiles counts.
HWY_INLINE int tile_count(const ShadowSweep &s, const std::vector<int> &table, const Window &window) {
    constexpr int k = ShadowTiles::kTilePx;
    const int c0 = std::max(window.x_lo, 0) / k, c1 = std::min(window.x_hi, s.layout.width - 1) / k + 1;
    const int r0 = std::max(window.y_lo, 0) / k, r1 = std::min(window.y_hi, s.layout.height - 1) / k + 1;
    const std::size_t stride = std::size_t(s.scratch->tiles.columns) + 1;
    const auto at = [&](int r, int c) { return table[std::size_t(r) * stride + std::size_t(c)]; };
    return at(r1, c1) - at(r0, c1) - at(r1, c0) + at(r0, c0);
}

/// Whether every pixel of `window` is exactly 1 or every one exactly +0: a
/// gather within it returns that value (the weighted sum of ones is the sum
/// of the weights, of zeros zero), which is also the lanes' own.
HWY_INLINE bool uniform(const ShadowSweep &s, const Window &window) {
    const ShadowTiles &tiles = s.scratch->tiles;
    return s.pass_over_uniform &&
           (tile_count(s, tiles.not_lit, window) == 0 || tile_count(s, tiles.not_dark, window) == 0);
}

/// One vector of pixels: the search (ISG Eq. 4-7), then the gather (ISG Eq.
/// 4, 8-9) of the lanes that found an occluder; the others keep `hard0`.
/// Blocks whose taps stay where no search can find an occluder, or where
/// every gather returns the lanes' own value, skip that work (ShadowTiles).
/// Radii are zeroed outside the lanes that use them, which then reach no further.
HWY_INLINE VF shadow_pixels(const ShadowSweep &s, const ShadowBlock &b, MF valid, const Point &p0, VF z_eye,
                            VF hard0) {
    const DF df;
    if (hn::AllFalse(df, valid)) return hard0;
    const VF search_px = hn::IfThenElseZero(valid, shadow_search_radius(s, z_eye));
    const Window search_window = tap_window(b.lanes, *s.search, search_px);
    if (s.pass_over_uniform && tile_count(s, s.scratch->tiles.in_shadow, search_window) == 0) return hard0;
    if (uniform(s, tap_window(b.lanes, *s.gather, hn::Set(df, s.range.max_radius_px)))) return hard0;
    VF occluder_m;
    const MF found = interior(b, search_window)
                         ? shadow_search<true>(s, b, valid, p0, search_px, occluder_m)
                         : shadow_search<false>(s, b, valid, p0, search_px, occluder_m);
    if (hn::AllFalse(df, found)) return hard0;
    const VF gather_px = hn::IfThenElseZero(found, shadow_gather_radius(s, p0, z_eye, occluder_m));
    const Window gather_window = tap_window(b.lanes, *s.gather, gather_px);
    if (uniform(s, gather_window)) return hard0;
    return interior(b, gather_window) ? shadow_gather<true>(s, b, found, p0, gather_px, hard0)
                                      : shadow_gather<false>(s, b, found, p0, gather_px, hard0);
}

/// Packs row `y`: (P, V) and (P, d) per pixel. d = -1 where the search
/// passes the pixel over (not in shadow, or no distance >= 0 and finite);
/// where V is not finite, the gather's P.x is NaN (so is the tap's weight,
/// which passes it over) and V 0, so that every packed value is finite.
void PackShadowRow(const ShadowSweep &s, ShadowScratch &scratch, int y) {
    const DF df;
    const std::ptrdiff_t row = std::ptrdiff_t(y) * s.layout.width;
    float *position_hard = scratch.position_hard.data() + 4 * row;
    float *position_occluder = scratch.position_occluder.data() + 4 * row;
    for (int x0 = 0; x0 < s.layout.width; x0 += int(hn::Lanes(df))) {
        const RowLanes lanes = row_lanes(s.layout, x0, y);
        const VF hard = load_centre(s.hard, lanes), d = load_centre(s.occluder_m, lanes);
        const MF searched = hn::And(hn::Lt(hard, hn::Set(df, 0.5f)),  // inShadow of ISG Eq. 6
                                    hn::And(hn::Ge(d, hn::Zero(df)), hn::IsFinite(d)));
        const MF finite = hn::IsFinite(hard);
        const VF x_m = load_centre(s.position[0], lanes);
        HWY_ALIGN float x[kMaxLanes], x_gather[kMaxLanes], y_m[kMaxLanes], z[kMaxLanes], v[kMaxLanes],
            occluder[kMaxLanes];
        hn::Store(x_m, df, x);
        hn::Store(hn::IfThenElse(finite, x_m, hn::Set(df, NAN)), df, x_gather);
        hn::Store(load_centre(s.position[1], lanes), df, y_m);
        hn::Store(load_centre(s.position[2], lanes), df, z);
        hn::Store(hn::IfThenElseZero(finite, hard), df, v);
        hn::Store(hn::IfThenElse(searched, d, hn::Set(df, -1.0f)), df, occluder);
        for (int i = 0; i < lanes.count; ++i) {
            float *q = position_hard + 4 * std::ptrdiff_t(x0 + i);
            float *o = position_occluder + 4 * std::ptrdiff_t(x0 + i);
            q[0] = x_gather[i];
            o[0] = x[i];
            q[1] = o[1] = y_m[i];
            q[2] = o[2] = z[i];
            q[3] = v[i];
            o[3] = occluder[i];
        }
    }
}

void ShadowRow(const ShadowSweep &s, int y) {
    const DF df;
    const DI di;
    const PlaneLayout dense = {s.layout.width, s.layout.height, s.layout.width, 1};
    for (int x0 = 0; x0 < s.layout.width; x0 += int(hn::Lanes(df))) {
        const ShadowBlock b = {row_lanes(s.layout, x0, y), dense, hn::Iota(di, y * dense.width + x0)};
        const RowLanes &lanes = b.lanes;
        const VF hard0 = load_centre(s.hard, lanes), z_eye = load_centre(s.depth_m, lanes);
        const Point p0 = load_centre_point(s.position, lanes);
        const MF valid = hn::And(
            lanes.in_row, hn::And(hn::And(hn::Gt(z_eye, hn::Zero(df)), hn::IsFinite(z_eye)), all_finite(p0)));
        store(shadow_pixels(s, b, valid, p0, z_eye, hard0), s.out, lanes);
    }
}

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
#include <cstring>
#include <string>

#include "aaf/core/util/error.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/parallel.h"

namespace aaf::isg {

HWY_EXPORT(ShadowRow);
HWY_EXPORT(PackShadowRow);
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

void shadow_row(const ShadowSweep &sweep, int y) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(ShadowRow)(sweep, y);
}

namespace {

/// Summed-area table of `flags` (columns x rows) into `table`, a zero row and column first.
void summed_area(const std::vector<unsigned char> &flags, int columns, int rows, std::vector<int> &table) {
    const std::size_t stride = std::size_t(columns) + 1;
    table.assign(stride * (std::size_t(rows) + 1), 0);
    for (std::size_t r = 1; r <= std::size_t(rows); ++r) {
        int row_sum = 0;
        for (std::size_t c = 1; c <= std::size_t(columns); ++c) {
            row_sum += flags[(r - 1) * std::size_t(columns) + c - 1];
            table[r * stride + c] = table[(r - 1) * stride + c] + row_sum;
        }
    }
}

}  // namespace

void prepare_shadow_sweep(ShadowSweep &sweep, ShadowScratch &scratch) {
    (void)instruction_set();
    const PlaneLayout &layout = sweep.layout;
    if (std::ptrdiff_t(layout.width) * layout.height > std::numeric_limits<int>::max() / 8)
        throw Error("an image of " + std::to_string(layout.width) + " x " + std::to_string(layout.height) +
                    " pixels is too large for the ISG methods");
    const std::size_t pixels = std::size_t(layout.width) * std::size_t(layout.height);
    scratch.position_hard.resize(4 * pixels);
    scratch.position_occluder.resize(4 * pixels);
    ShadowTiles &tiles = scratch.tiles;
    constexpr int k = ShadowTiles::kTilePx;
    tiles.columns = (layout.width + k - 1) / k;
    tiles.rows = (layout.height + k - 1) / k;
    const std::size_t count = std::size_t(tiles.columns) * std::size_t(tiles.rows);
    std::vector<unsigned char> in_shadow(count, 0), not_lit(count, 0), not_dark(count, 0);
    const std::uint32_t one_bits = 0x3f800000u;  // 1.0f
    // One tile row per task: its rows packed, then its tiles' flags from the rows just read.
    parallel_for_rows(tiles.rows, [&](int tile_row) {
        const int y_end = std::min(layout.height, (tile_row + 1) * k);
        const std::size_t tiles_at = std::size_t(tile_row) * std::size_t(tiles.columns);
        for (int y = tile_row * k; y < y_end; ++y) {
            HWY_DYNAMIC_DISPATCH(PackShadowRow)(sweep, scratch, y);
            const float *row = sweep.hard + std::ptrdiff_t(y) * layout.row_stride;
            for (int x = 0; x < layout.width; ++x) {
                const float v = row[std::ptrdiff_t(x) * layout.pixel_stride];
                std::uint32_t bits;
                std::memcpy(&bits, &v, sizeof bits);
                const std::size_t tile = tiles_at + std::size_t(x / k);
                in_shadow[tile] |= (v < 0.5f);  // ISG Eq. 6's inShadow, as the search tests it
                not_lit[tile] |= (bits != one_bits);
                not_dark[tile] |= (bits != 0);
            }
        }
    });
    summed_area(in_shadow, tiles.columns, tiles.rows, tiles.in_shadow);
    summed_area(not_lit, tiles.columns, tiles.rows, tiles.not_lit);
    summed_area(not_dark, tiles.columns, tiles.rows, tiles.not_dark);
    sweep.scratch = &scratch;
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
