// The ratio estimator's joint bilateral passes and noise estimate lines
// (ratio_rows.h) for every instruction set Google Highway targets, chosen at
// run time. Neighbouring centre pixels share the lanes, each summing its own
// taps in the scalar order with multiplies and adds kept apart (this file is
// built without contraction), so every instruction set gives the same bits.
#include "aaf/core/methods/ratio/ratio_rows.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

// As gather_rows.cpp: no scalable (SVE, RVV) targets.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/ratio/ratio_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using VI = hn::Vec<DI>;
constexpr int kMaxLanes = int(HWY_LANES(float));
static_assert(kMaxLanes <= int(kRatioPlaneSlack), "the slack covers a vector");

/// fast_exp_nonpositive (fast_exp.h) lane by lane, operation for operation
/// (its Taylor polynomial and separate roundings), so every lane gives that
/// function's bits. Its truncating int conversion is Trunc here (the same
/// integer, never out of range: k lies in [-126, 0]), and 2^k's exponent
/// bits come from k + 2^23 + 127, whose low mantissa bits hold k + 127: no
/// int conversions, whose out-of-range fix-ups cost more than the rest.
HWY_INLINE V fast_exp_nonpositive(D d, V x) {
    const DI di;
    // Max(NaN, -87) is -87 as the scalar comparison; Min(-0, 0) may keep -0
    // where the scalar gives 0: both round to k = 0 and the same polynomial
    // (as does Trunc's -0 where the conversion gives +0: r and p are the same).
    const V clamped = hn::Min(hn::Max(x, hn::Set(d, -87.0f)), hn::Zero(d));
    const V k = hn::Trunc(hn::Sub(hn::Mul(clamped, hn::Set(d, 1.44269504088896341f)), hn::Set(d, 0.5f)));
    const V r = hn::Sub(hn::Sub(clamped, hn::Mul(k, hn::Set(d, 0.693145751953125f))),
                        hn::Mul(k, hn::Set(d, 1.428606765330187045e-06f)));
    V p = hn::Set(d, 1.0f / 720.0f);
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f / 120.0f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f / 24.0f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f / 6.0f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 0.5f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f));
    // k + 2^23 + 127 is exact, its bits 0x4b000000 + k + 127; shifting by 23 drops the 0x4b.
    const VI biased = hn::BitCast(di, hn::Add(k, hn::Set(d, 8388735.0f)));
    return hn::Mul(p, hn::BitCast(d, hn::ShiftLeft<23>(biased)));
}

/// Lanes [0, n) of `from`, zeros after (a row's last, partial vector).
HWY_INLINE V load_part(const float *from, int n) {
    const D d;
    if (n == int(hn::Lanes(d))) return hn::LoadU(d, from);
    alignas(64) float lane[kMaxLanes] = {};
    std::copy_n(from, n, lane);
    return hn::Load(d, lane);
}

/// Stores lanes [0, n) of `v`, nothing after (the next row may be another thread's).
template <class DV, class VV, typename T>
HWY_INLINE void store_part(DV dv, VV v, T *to, int n) {
    if (n == int(hn::Lanes(dv))) return hn::StoreU(v, dv, to);
    alignas(64) T lane[kMaxLanes];
    hn::Store(v, dv, lane);
    std::copy_n(lane, n, to);
}

/// One vector of the guides' per-pixel values (ratio_planes_row's and the passes' centres).
struct GuideLanes {
    V px, py, pz, nx, ny, nz, plane_m, inv_scale, minus_half_inv_sigma_sq;
    VI radius;
};

/// The guides of pixels [x0, x0 + n) of `in`, lane by lane: square roots and
/// quotients are correctly rounded on every instruction set, the sums kept in order.
HWY_INLINE GuideLanes guide_lanes(const RatioGuideRow &in, int x0, int n, float reach_cap_px) {
    const D d;
    const DI di;
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), plane_sigma = hn::Set(d, in.plane_sigma);
    const V cutoff = hn::Set(d, in.cutoff_sigmas), reach_cap = hn::Set(d, reach_cap_px);
    const V p0 = load_part(in.position[0] + x0, n), p1 = load_part(in.position[1] + x0, n),
            p2 = load_part(in.position[2] + x0, n);
    const V n0 = load_part(in.normal[0] + x0, n), n1 = load_part(in.normal[1] + x0, n),
            n2 = load_part(in.normal[2] + x0, n);
    const V scale = load_part(in.scale_m + x0, n), sigma = load_part(in.sigma_px + x0, n);
    const V length = hn::Sqrt(hn::Add(hn::Add(hn::Mul(n0, n0), hn::Mul(n1, n1)), hn::Mul(n2, n2)));
    const auto surface = hn::And(hn::And(hn::Gt(scale, zero), hn::IsFinite(scale)),
                                 hn::And(hn::IsFinite(hn::Add(hn::Add(p0, p1), p2)),
                                         hn::And(hn::Gt(length, zero), hn::IsFinite(length))));
    const V nx = hn::Div(n0, length), ny = hn::Div(n1, length), nz = hn::Div(n2, length);
    const V plane_m = hn::Add(hn::Add(hn::Mul(nx, p0), hn::Mul(ny, p1)), hn::Mul(nz, p2));
    const V inv_scale = hn::IfThenElseZero(surface, hn::Div(one, hn::Mul(plane_sigma, scale)));
    // A tap reaching past the image adds nothing: the reach is capped there.
    const auto filtered = hn::And(hn::And(hn::Gt(sigma, zero), hn::IsFinite(sigma)), hn::Ne(inv_scale, zero));
    const VI radius = hn::ConvertTo(di, hn::Min(hn::Ceil(hn::Mul(cutoff, sigma)), reach_cap));
    return {hn::IfThenElseZero(surface, p0),
            hn::IfThenElseZero(surface, p1),
            hn::IfThenElseZero(surface, p2),
            hn::IfThenElseZero(surface, nx),
            hn::IfThenElseZero(surface, ny),
            hn::IfThenElseZero(surface, nz),
            hn::IfThenElseZero(surface, plane_m),
            inv_scale,
            hn::IfThenElseZero(filtered, hn::Div(hn::Set(d, -0.5f), hn::Mul(sigma, sigma))),
            hn::IfThenElseZero(hn::RebindMask(di, filtered), radius)};
}

/// The centre pixels of the lanes: their tangent planes, Gaussians and tap ranges.
struct Centres {
    V nx, ny, nz, plane_m, inv_scale, minus_half_inv_sigma_sq;
    VI radius;
    VI lo, hi;       ///< the first and last tap offset of each lane
    V lo_px, hi_px;  ///< the same as floats (exact), to compare with
};

/// The centres' data from their guides (lanes [0, n) of `in` from `i` on),
/// computed only for the vectors that filter.
HWY_INLINE Centres load_centres(const RatioGuideRow &in, int i, int n, VI radius) {
    const GuideLanes g = guide_lanes(in, i, n, 0.0f);  // the reach comes from the planes
    return {g.nx,   g.ny,           g.nz,           g.plane_m,     g.inv_scale,  g.minus_half_inv_sigma_sq,
            radius, hn::Zero(DI()), hn::Zero(DI()), hn::Zero(D()), hn::Zero(D())};
}

/// Where the taps' guides and values start (offset 0 at the lanes' centres).
struct Taps {
    const float *px, *py, *pz, *inv_scale;
    const float *source[kRatioMaxPlanes];
};

/// Taps whose weights add_taps computes before it sums them: their
/// exponentials are independent, so they overlap in the core instead of
/// waiting on one another's latency chains (the same operations per lane).
constexpr int kTapsPerBatch = 8;

/// Adds the taps at offsets [o_begin, o_end] `stride` floats apart, each lane
/// only those in its [lo, hi], in order (ratio_bilateral.cpp's scalar loops:
/// the weight exp(-o^2 / (2 sigma^2) - q^2 / 2) of a tap q plane sigmas from
/// the centre's tangent plane, 0 off a surface, 1 at the centre). A tap
/// outside a lane's range weighs 0 there: with finite values it adds +0 or
/// -0, which leaves every sum as it was (a sum that starts at +0 is never -0).
template <int K>
HWY_INLINE void add_taps(const Centres &c, const Taps &taps, std::ptrdiff_t stride, int o_begin, int o_end,
                         V (&sums)[K], V &weight_sum) {
    const D d;
    for (int k = 0; k < K; ++k) sums[k] = hn::Zero(d);
    weight_sum = hn::Zero(d);
    const V half = hn::Set(d, 0.5f), zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    for (int o0 = o_begin; o0 <= o_end; o0 += kTapsPerBatch) {
        const int batch = std::min(kTapsPerBatch, o_end - o0 + 1);
        V weights[kTapsPerBatch];
        for (int j = 0; j < batch; ++j) {
            const int o = o0 + j;
            const std::ptrdiff_t t = std::ptrdiff_t(o) * stride;
            const V o_px = hn::Set(d, float(o));
            const V plane_m = hn::Add(
                hn::Add(hn::Mul(c.nx, hn::LoadU(d, taps.px + t)), hn::Mul(c.ny, hn::LoadU(d, taps.py + t))),
                hn::Mul(c.nz, hn::LoadU(d, taps.pz + t)));
            const V q = hn::Mul(hn::Sub(plane_m, c.plane_m), c.inv_scale);
            const V exponent = hn::Sub(hn::Mul(hn::Mul(c.minus_half_inv_sigma_sq, o_px), o_px),
                                       hn::Mul(hn::Mul(half, q), q));
            const auto counts = hn::And(hn::And(hn::Ge(o_px, c.lo_px), hn::Le(o_px, c.hi_px)),
                                        hn::Ne(hn::LoadU(d, taps.inv_scale + t), zero));
            // The centre always counts (o = 0 lies in every lane's range).
            weights[j] = o == 0 ? one : hn::IfThenElseZero(counts, fast_exp_nonpositive(d, exponent));
        }
        for (int j = 0; j < batch; ++j) {
            const std::ptrdiff_t t = std::ptrdiff_t(o0 + j) * stride;
            weight_sum = hn::Add(weight_sum, weights[j]);
            for (int k = 0; k < K; ++k)
                sums[k] = hn::Add(sums[k], hn::Mul(weights[j], hn::LoadU(d, taps.source[k] + t)));
        }
    }
}

/// The lanes' filtered values: the sums over the weight, or the centre's own
/// value where the radius is 0 (bit for bit, -0 included); lanes [0, n) to
/// to[k], plane after plane.
template <int K>
HWY_INLINE void finish(const Centres &c, const Taps &taps, const V (&sums)[K], V weight_sum,
                       float *const (&to)[K], int n) {
    const D d;
    const auto keep = hn::RebindMask(d, hn::Eq(c.radius, hn::Zero(DI())));
    for (int k = 0; k < K; ++k)
        store_part(d, hn::IfThenElse(keep, hn::LoadU(d, taps.source[k]), hn::Div(sums[k], weight_sum)), to[k],
                   n);
}

/// Sets the lanes' tap range [lo, hi] (offsets from the centres).
HWY_INLINE void set_range(Centres &c, VI lo, VI hi) {
    const D d;
    c.lo = lo;
    c.hi = hi;
    c.lo_px = hn::ConvertTo(d, lo);
    c.hi_px = hn::ConvertTo(d, hi);
}

/// The reach of lanes [0, n) of `radius`, 0 for the others.
HWY_INLINE VI load_radius(const std::int32_t *radius, int n) {
    const DI di;
    return hn::IfThenElseZero(hn::FirstN(di, std::size_t(n)), hn::LoadU(di, radius));
}

/// Where the vectors from `x0` on (pixels x0 .. x_end - 1 of `radius`)
/// stop being ones no pixel of which filters: x0 itself, or the end of such
/// a span (at most x_end), which the passes copy at once.
HWY_INLINE int end_of_copied_span(const std::int32_t *radius, int x0, int x_end) {
    const DI di;
    const int lanes = int(hn::Lanes(di));
    while (x0 < x_end) {
        const int n = std::min(lanes, x_end - x0);
        if (!hn::AllTrue(di, hn::Eq(load_radius(radius + x0, n), hn::Zero(di)))) return x0;
        x0 += n;
    }
    return x_end;
}

template <int K>
void row_x(const RatioBilateralSweep &s, int y, const float *const *source_rows,
           const RatioGuideRow &centres) {
    const D d;
    const DI di;
    const int lanes = int(hn::Lanes(d));
    const RatioBilateralPlanes &p = *s.planes;
    const int width = p.width;
    const std::size_t row = std::size_t(y) * std::size_t(width);
    const std::int32_t *radius = &p.radius_px[row];
    const int reach = std::max(0, *std::max_element(radius, radius + width));
    // A lane's taps lie in the row (lo >= -x, hi <= width - 1 - x), but a
    // vector's loads run from its first lane's lowest tap to its last lane's
    // highest plus a vector: the vectors that may read before the row's
    // start (x0 < head_end) or past its end (x0 >= tail_x0) load from a copy
    // of their part of the row with zeros around it; the others from the row
    // itself. Where the two meet, one copy serves the whole row.
    const int head_end = std::min(width, (reach + lanes - 1) / lanes * lanes);
    const int first_tail_x0 = std::max(0, width - reach - lanes + 1);
    int tail_x0 = std::min(width, (first_tail_x0 + lanes - 1) / lanes * lanes);
    const bool one_copy = tail_x0 <= head_end;
    if (one_copy) tail_x0 = width;
    const int copy_end = one_copy ? width : head_end;  // the head copy's vectors: [0, copy_end)
    const int front = reach, back = reach + lanes;
    const std::size_t head_floats = std::size_t(front + std::min(width, copy_end + back) + back);
    const std::size_t tail_floats = std::size_t(front + (width - std::max(0, tail_x0 - reach)) + back);
    const std::size_t slot = std::max(head_floats, tail_floats);
    thread_local std::vector<float> scratch;
    scratch.resize(std::max(scratch.size(), slot * std::size_t(2 * (4 + K))));
    // The row's [from, to) copied with `front` zeros before and `back` after, indexed by x as the row.
    auto padded = [&](int index, const float *row_values, int from, int to) {
        float *copy = &scratch[std::size_t(index) * slot];
        std::fill_n(copy, front, 0.0f);
        std::memcpy(copy + front, row_values + from, std::size_t(to - from) * sizeof(float));
        std::fill_n(copy + front + (to - from), back, 0.0f);
        return copy + front - from;
    };
    const Taps in_row{&p.px[row], &p.py[row], &p.pz[row], &p.inv_scale[row], {}};
    auto copied_taps = [&](int first_index, int from, int to) {
        Taps taps{padded(first_index, in_row.px, from, to),
                  padded(first_index + 1, in_row.py, from, to),
                  padded(first_index + 2, in_row.pz, from, to),
                  padded(first_index + 3, in_row.inv_scale, from, to),
                  {}};
        for (int k = 0; k < K; ++k) taps.source[k] = padded(first_index + 4 + k, source_rows[k], from, to);
        return taps;
    };
    Taps head{nullptr, nullptr, nullptr, nullptr, {}}, tail = head;
    if (copy_end > 0) head = copied_taps(0, 0, std::min(width, copy_end + reach + lanes));
    if (tail_x0 < width) tail = copied_taps(4 + K, std::max(0, tail_x0 - reach), width);
    const VI last = hn::Set(di, width - 1);
    for (int x0 = 0; x0 < width; x0 += lanes) {
        const int copied_end = end_of_copied_span(radius, x0, width);
        if (copied_end > x0) {  // pixels that keep their values
            for (int k = 0; k < K; ++k)
                std::memcpy(s.output[k] + row + std::size_t(x0), source_rows[k] + x0,
                            std::size_t(copied_end - x0) * sizeof(float));
            x0 = copied_end;
            if (x0 == width) break;
        }
        const int n = std::min(lanes, width - x0);
        Centres c = load_centres(centres, x0, n, load_radius(radius + x0, n));
        const VI x = hn::Iota(di, x0);
        set_range(c, hn::Max(hn::Neg(c.radius), hn::Neg(x)), hn::Min(c.radius, hn::Sub(last, x)));
        Taps at = in_row;
        for (int k = 0; k < K; ++k) at.source[k] = source_rows[k];
        if (x0 >= tail_x0) at = tail;
        if (x0 < copy_end && head.px) at = head;
        for (const float **plane : {&at.px, &at.py, &at.pz, &at.inv_scale}) *plane += x0;
        for (int k = 0; k < K; ++k) at.source[k] += x0;
        V sums[K], weight_sum;
        add_taps<K>(c, at, 1, hn::GetLane(hn::MinOfLanes(di, c.lo)), hn::GetLane(hn::MaxOfLanes(di, c.hi)),
                    sums, weight_sum);
        float *to[K];
        for (int k = 0; k < K; ++k) to[k] = s.output[k] + row + std::size_t(x0);
        finish<K>(c, at, sums, weight_sum, to, n);
    }
}

template <int K>
void row_y(const RatioBilateralSweep &s, int y, int x_begin, int x_end, float *values,
           const RatioGuideRow &centres) {
    const D d;
    const DI di;
    const int lanes = int(hn::Lanes(d));
    const RatioBilateralPlanes &p = *s.planes;
    const std::ptrdiff_t width = p.width;
    const std::size_t row = std::size_t(y) * std::size_t(width), span = std::size_t(x_end - x_begin);
    const std::int32_t *radius = &p.radius_px[row];
    const VI up = hn::Set(di, -y), down = hn::Set(di, p.height - 1 - y);
    for (int x0 = x_begin; x0 < x_end; x0 += lanes) {
        const int copied_end = end_of_copied_span(radius, x0, x_end);
        if (copied_end > x0) {  // pixels that keep their values
            for (int k = 0; k < K; ++k)
                std::memcpy(values + std::size_t(k) * span + std::size_t(x0 - x_begin),
                            s.source[k] + row + x0, std::size_t(copied_end - x0) * sizeof(float));
            x0 = copied_end;
            if (x0 == x_end) break;
        }
        const int n = std::min(lanes, x_end - x0);
        const std::size_t c0 = row + std::size_t(x0);
        Centres c = load_centres(centres, x0 - x_begin, n, load_radius(radius + x0, n));
        set_range(c, hn::Max(hn::Neg(c.radius), up), hn::Min(c.radius, down));
        Taps at{&p.px[c0], &p.py[c0], &p.pz[c0], &p.inv_scale[c0], {}};
        for (int k = 0; k < K; ++k) at.source[k] = s.source[k] + c0;
        V sums[K], weight_sum;
        add_taps<K>(c, at, width, hn::GetLane(hn::MinOfLanes(di, c.lo)),
                    hn::GetLane(hn::MaxOfLanes(di, c.hi)), sums, weight_sum);
        float *to[K];
        for (int k = 0; k < K; ++k) to[k] = values + std::size_t(k) * span + std::size_t(x0 - x_begin);
        finish<K>(c, at, sums, weight_sum, to, n);
    }
}

/// row_x or row_y with the plane count a compile-time constant (the sums stay in registers).
template <template <int> class Pass, typename... Args>
void with_count(int count, Args &&...args) {
    switch (count) {
        case 1:
            return Pass<1>::run(args...);
        case 2:
            return Pass<2>::run(args...);
        case 3:
            return Pass<3>::run(args...);
        case 4:
            return Pass<4>::run(args...);
        case 5:
            return Pass<5>::run(args...);
        case 6:
            return Pass<6>::run(args...);
        case 7:
            return Pass<7>::run(args...);
        default:
            return Pass<8>::run(args...);
    }
}

template <int K>
struct RowX {
    static void run(const RatioBilateralSweep &s, int y, const float *const *source_rows,
                    const RatioGuideRow &centres) {
        row_x<K>(s, y, source_rows, centres);
    }
};
template <int K>
struct RowY {
    static void run(const RatioBilateralSweep &s, int y, int x_begin, int x_end, float *values,
                    const RatioGuideRow &centres) {
        row_y<K>(s, y, x_begin, x_end, values, centres);
    }
};

void RatioBilateralRowX(const RatioBilateralSweep &s, int y, const float *const *source_rows,
                        const RatioGuideRow &centres) {
    with_count<RowX>(s.count, s, y, source_rows, centres);
}

void RatioBilateralRowY(const RatioBilateralSweep &s, int y, int x_begin, int x_end, float *values,
                        const RatioGuideRow &centres) {
    with_count<RowY>(s.count, s, y, x_begin, x_end, values, centres);
}

/// ratio_bilateral.cpp's per-pixel tap planes.
void RatioPlanesRow(const RatioGuideRow &in, int y, RatioBilateralPlanes &p) {
    const D d;
    const DI di;
    const int lanes = int(hn::Lanes(d)), width = p.width;
    const std::size_t row = std::size_t(y) * std::size_t(width);
    for (int x0 = 0; x0 < width; x0 += lanes) {
        const int n = std::min(lanes, width - x0);
        const GuideLanes g = guide_lanes(in, x0, n, float(std::max(width, p.height)));
        const std::size_t c = row + std::size_t(x0);
        store_part(d, g.px, &p.px[c], n);
        store_part(d, g.py, &p.py[c], n);
        store_part(d, g.pz, &p.pz[c], n);
        store_part(d, g.inv_scale, &p.inv_scale[c], n);
        store_part(di, g.radius, &p.radius_px[c], n);
    }
}

/// ratio_compose_row in lanes: quotients, comparisons and products are
/// correctly rounded everywhere, so every lane gives the scalar's bits
/// (a NaN quotient passes both clamps, as there).
void RatioComposeRow(const float *u, const float *s_den, const float *u_den, int count, bool accumulate,
                     float *rgb) {
    const D d;
    const int lanes = int(hn::Lanes(d));
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    for (int x = 0; x < count; x += lanes) {
        const int n = std::min(lanes, count - x);
        const V u_n = load_part(u_den + x, n), quotient = hn::Div(load_part(s_den + x, n), u_n);
        const V clamped = hn::IfThenElse(hn::Lt(quotient, zero), zero,
                                         hn::IfThenElse(hn::Gt(quotient, one), one, quotient));
        V out = hn::Mul(load_part(u + x, n), hn::IfThenElse(hn::Gt(u_n, zero), clamped, one));
        if (accumulate) out = hn::Add(load_part(rgb + x, n), out);
        store_part(d, out, rgb + x, n);
    }
}

/// The 3x3 box's interior columns in lanes (each sum in the scalar order),
/// its first and last column and short rows one by one.
void RatioBoxRow(const float *const *rows, int row_count, int width, float *out) {
    const D d;
    const int lanes = int(hn::Lanes(d));
    auto scalar = [&](int x) {
        float sum = 0.0f;
        int count = 0;
        for (int r = 0; r < row_count; ++r)
            for (int tx = std::max(0, x - 1); tx <= std::min(width - 1, x + 1); ++tx) {
                sum += rows[r][tx];
                ++count;
            }
        out[x] = sum / float(count);
    };
    scalar(0);
    int x = 1;
    const V count = hn::Set(d, float(3 * row_count));
    for (; x + lanes <= width - 1; x += lanes) {
        V sum = hn::Zero(d);
        for (int r = 0; r < row_count; ++r) {
            sum = hn::Add(sum, hn::LoadU(d, rows[r] + x - 1));
            sum = hn::Add(sum, hn::LoadU(d, rows[r] + x));
            sum = hn::Add(sum, hn::LoadU(d, rows[r] + x + 1));
        }
        hn::StoreU(hn::Div(sum, count), d, out + x);
    }
    for (; x < width; ++x) scalar(x);
}

/// The offsets in the padded copy from a pixel to the nearest pixels of its
/// line's taps t = -radius .. radius along `direction` (x, y), in lanes of
/// t: floor(t direction + 1/2) rounded apart, as one float at a time would.
HWY_INLINE void line_offsets(const float (&direction)[2], int radius, std::int32_t row_floats,
                             std::int32_t *offsets) {
    const D d;
    const DI di;
    const V half = hn::Set(d, 0.5f), along_x = hn::Set(d, direction[0]), along_y = hn::Set(d, direction[1]);
    for (int t0 = -radius; t0 <= radius; t0 += int(hn::Lanes(d))) {
        const V t = hn::ConvertTo(d, hn::Iota(di, t0));
        const VI dx = hn::ConvertTo(di, hn::Floor(hn::Add(hn::Mul(t, along_x), half)));
        const VI dy = hn::ConvertTo(di, hn::Floor(hn::Add(hn::Mul(t, along_y), half)));
        hn::StoreU(hn::Add(hn::Mul(dy, hn::Set(di, row_floats)), dx), di, offsets + (t0 + radius));
    }
}

/// Whether any of `count` bytes is non-zero (a whole run as one word).
HWY_INLINE bool any_active(const unsigned char *active, int count) {
    static_assert(kRatioNoiseRunPx == sizeof(std::uint64_t), "a run's flags are one word");
    if (count == kRatioNoiseRunPx) {
        std::uint64_t word;
        std::memcpy(&word, active, sizeof word);
        return word != 0;
    }
    return std::find_if(active, active + count, [](unsigned char a) { return a != 0; }) != active + count;
}

/// The raw E of the row's active pixels (ratio estimator Eq. 29): along 4
/// lines 45 degrees apart, turned by one hashed angle per run of
/// kRatioNoiseRunPx pixels, the mean absolute second difference of W_N over
/// nearest-pixel taps (the padded copy repeats the edges and reads
/// non-finite values as 1). A run's pixels tap at the same offsets, so each
/// tap is one vector load; lanes never span two runs.
void RatioNoiseRow(const RatioNoiseSweep &s, int y, const unsigned char *active, float *raw) {
    const hn::CappedTag<float, kRatioNoiseRunPx> d;
    const hn::Rebind<std::int32_t, decltype(d)> d32;
    const hn::Rebind<std::uint8_t, decltype(d)> d8;
    using VN = hn::Vec<decltype(d)>;
    const int lanes = int(hn::Lanes(d)), radius = s.line_radius_px, taps = 2 * radius + 1;
    const float per_difference = 1.0f / float(taps - 2);
    constexpr float kQuarterPi = 0.78539816f, kHalfSqrt2 = 0.70710678f;
    const auto two = hn::Set(d, 2.0f);
    // The row's centre pixel (x = 0) in the padded copy.
    const float *centre = s.padded + std::size_t(y + radius) * s.padded_row_floats + std::size_t(radius);
    const std::int32_t row_floats = std::int32_t(s.padded_row_floats);
    thread_local std::vector<std::int32_t> offsets;     // per line, per tap: from a pixel to its tap
    offsets.resize(std::size_t(4 * taps + kMaxLanes));  // a vector past the last
    std::fill_n(raw, s.width, 0.0f);
    for (int x0 = 0; x0 < s.width; x0 += kRatioNoiseRunPx) {
        const int run = std::min(kRatioNoiseRunPx, s.width - x0);
        if (!any_active(active + x0, run)) continue;
        const float turn = ratio_pixel_random(x0 / kRatioNoiseRunPx, y, s.seed) * kQuarterPi;
        const float c = std::cos(turn), sn = std::sin(turn);
        const float directions[4][2] = {{c, sn},
                                        {kHalfSqrt2 * (c - sn), kHalfSqrt2 * (c + sn)},
                                        {-sn, c},
                                        {-kHalfSqrt2 * (c + sn), kHalfSqrt2 * (c - sn)}};
        for (int line = 0; line < 4; ++line)
            line_offsets(directions[line], radius, row_floats, &offsets[std::size_t(line * taps)]);
        for (int l0 = 0; l0 < run; l0 += lanes) {
            const float *at_pixel = centre + x0 + l0;  // lanes past the row's end read its padding
            // ratio estimator Eq. 29: the integral of |d^2 W_N / dt^2| along each
            // line, the 4 lines side by side (independent sums that overlap in the core).
            const std::int32_t *offset = offsets.data();  // line l's tap i at offset[l taps + i]
            VN before[4], at[4], variation[4];
            for (int line = 0; line < 4; ++line) {
                before[line] = hn::LoadU(d, at_pixel + offset[line * taps]);
                at[line] = hn::LoadU(d, at_pixel + offset[line * taps + 1]);
                variation[line] = hn::Zero(d);
            }
            for (int i = 2; i < taps; ++i)
                for (int line = 0; line < 4; ++line) {
                    const VN after = hn::LoadU(d, at_pixel + offset[line * taps + i]);
                    variation[line] =
                        hn::Add(variation[line],
                                hn::Abs(hn::Add(hn::Sub(before[line], hn::Mul(two, at[line])), after)));
                    before[line] = at[line];
                    at[line] = after;
                }
            auto sum = hn::Zero(d);
            for (int line = 0; line < 4; ++line)
                sum = hn::Add(sum, hn::Mul(variation[line], hn::Set(d, per_difference)));
            const auto mean = hn::Mul(hn::Set(d, 0.25f), sum);  // the mean over n = 4 lines
            if (l0 + lanes <= run) {                            // inactive lanes keep the row's +0
                const auto flags = hn::PromoteTo(d32, hn::LoadU(d8, active + x0 + l0));
                hn::StoreU(hn::IfThenElseZero(hn::RebindMask(d, hn::Ne(flags, hn::Zero(d32))), mean), d,
                           raw + x0 + l0);
                continue;
            }
            alignas(64) float out[kRatioNoiseRunPx] = {};  // GCC cannot see Store fill it
            hn::Store(mean, d, out);
            for (int l = 0; l < run - l0; ++l)
                if (active[x0 + l0 + l]) raw[x0 + l0 + l] = out[l];
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(RatioBilateralRowX);
HWY_EXPORT(RatioBilateralRowY);
HWY_EXPORT(RatioNoiseRow);
HWY_EXPORT(RatioPlanesRow);
HWY_EXPORT(RatioBoxRow);
HWY_EXPORT(RatioComposeRow);

void ratio_bilateral_row_x(const RatioBilateralSweep &sweep, int y, const float *const *source_rows,
                           const RatioGuideRow &centres) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(RatioBilateralRowX)(sweep, y, source_rows, centres);
}

void ratio_bilateral_row_y(const RatioBilateralSweep &sweep, int y, int x_begin, int x_end, float *values,
                           const RatioGuideRow &centres) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(RatioBilateralRowY)(sweep, y, x_begin, x_end, values, centres);
}

void ratio_noise_row(const RatioNoiseSweep &sweep, int y, const unsigned char *active, float *raw) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(RatioNoiseRow)(sweep, y, active, raw);
}

void ratio_planes_row(const RatioGuideRow &in, int y, RatioBilateralPlanes &planes) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(RatioPlanesRow)(in, y, planes);
}

void ratio_compose_row(const float *u, const float *s_den, const float *u_den, int count, bool accumulate,
                       float *rgb) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(RatioComposeRow)(u, s_den, u_den, count, accumulate, rgb);
}

void ratio_box_row(const float *const *rows, int row_count, int width, float *out) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(RatioBoxRow)(rows, row_count, width, out);
}

}  // namespace aaf::detail
#endif
