// What the ISG methods' per-pixel loops share (isg_rows.cpp,
// isg_shadow_rows.cpp), included once per instruction set (Highway's -inl.h
// convention): one pixel per lane, its taps read at rounded offsets, its
// sums in order.
#if defined(AAF_CORE_METHODS_ISG_ISG_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef AAF_CORE_METHODS_ISG_ISG_LANES_INL_H_
#undef AAF_CORE_METHODS_ISG_ISG_LANES_INL_H_
#else
#define AAF_CORE_METHODS_ISG_ISG_LANES_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <hwy/highway.h>

#include "isg_rows.h"

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

}  // namespace HWY_NAMESPACE
}  // namespace aaf::isg
HWY_AFTER_NAMESPACE();

#endif  // AAF_CORE_METHODS_ISG_ISG_LANES_INL_H_
