// The unmodulated gather's inner loops (gather_rows.h) for every instruction
// set Google Highway targets, chosen at run time. Highway is a private
// implementation dependency of aaf_core: no public header includes it.
#include "aaf/core/kernels/gather_rows.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>

// Arrays of vectors need sized vector types: no scalable (SVE, RVV) targets.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kernels/gather_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Partial sums per pixel; fast_exp.h's kLanes in the scalar loops it replaces.
constexpr int kSums = 8;
using D = hn::CappedTag<float, kSums>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
constexpr int kLanes = HWY_MIN(kSums, int(HWY_LANES(float)));
constexpr int kBlocks = kSums / kLanes;  ///< vectors per run of kSums taps

/// gather_exp_nonpositive (fast_exp.h) lane by lane, operation for
/// operation: Highway's MulAdd is one fused rounding where the target has
/// FMA (HWY_NATIVE_FMA: the scalar function's Fused) and a multiply then an
/// add elsewhere, so every lane gives that function's bits, for any lane count.
template <class DF>
HWY_INLINE hn::Vec<DF> gather_exp_nonpositive(DF d, hn::Vec<DF> x) {
    using VF = hn::Vec<DF>;
    const hn::RebindToSigned<DF> di;
    // Max and Min, one instruction each, give the scalar comparisons' bits:
    // Max(NaN, -87) is -87 as there, and where Min(-0, 0) keeps -0 instead
    // of the scalar 0, both give exp = 1 exactly.
    const VF above_floor = hn::Max(x, hn::Set(d, -87.0f));
    const VF clamped = hn::Min(above_floor, hn::Zero(d));
    const VF rounding_shift = hn::Set(d, 12582912.0f);  // 1.5 * 2^23
    const VF shifted = hn::MulAdd(clamped, hn::Set(d, 1.44269504088896341f), rounding_shift);
    const VF k = hn::Sub(shifted, rounding_shift);
    const VF r = hn::NegMulAdd(k, hn::Set(d, 1.428606765330187045e-06f),
                               hn::NegMulAdd(k, hn::Set(d, 0.693145751953125f), clamped));
    VF p = hn::Set(d, 0.00836377405f);
    p = hn::MulAdd(p, r, hn::Set(d, 0.0418798551f));
    p = hn::MulAdd(p, r, hn::Set(d, 0.166665733f));
    p = hn::MulAdd(p, r, hn::Set(d, 0.499993473f));
    p = hn::MulAdd(p, r, hn::Set(d, 1.0f));
    p = hn::MulAdd(p, r, hn::Set(d, 1.0f));
    const VF scale =
        hn::BitCast(d, hn::ShiftLeft<23>(hn::Sub(hn::BitCast(di, shifted), hn::Set(di, 0x4B400000 - 127))));
    return hn::Mul(p, scale);
}

/// The guides' planes one tap reads, from tap index `t` on.
struct TapPlanes {
    const float *u, *v, *n, *normal_x, *normal_y, *normal_z, *id;
};

/// What a centre pixel compares its taps with.
struct Centre {
    V u, v, n, shear_u, shear_v, inv_two_sigma_sq_n, normal_x, normal_y, normal_z, id, cos_threshold;
    /// -1 / (2 sigma^2), along v apart when the guides are anisotropic:
    /// negated once per centre, not per tap (the same bits: rounding is symmetric).
    V neg_inv_two_sigma_sq, neg_inv_two_sigma_sq_v;
    bool anisotropic = false;
};

/// One tap's weight for the centres `c` (Centre or WideCentres), given the
/// tap's guides: 0 where its object id or normal is rejected, else the
/// Gaussian exp(-(du^2 + dv^2) / (2 sigma^2)) (AAF Eq. 11), with the guides'
/// per-axis widths exp(-du^2 a_u - dv^2 a_v), and when sheared with du, dv
/// taken along the shear and the normal offset's own term. Every multiply
/// followed by an add is one MulAdd (fused where the target has FMA); the
/// tests' reference_pass writes the same operations out in scalar form.
template <bool Sheared, class DF, class Centres>
HWY_INLINE hn::Vec<DF> tap_weight(DF d, const Centres &c, hn::Vec<DF> cos_threshold, bool anisotropic,
                                  hn::Vec<DF> normal_x, hn::Vec<DF> normal_y, hn::Vec<DF> normal_z,
                                  hn::Vec<DF> id, hn::Vec<DF> u, hn::Vec<DF> v, hn::Vec<DF> n) {
    using VF = hn::Vec<DF>;
    const VF cos_angle =
        hn::MulAdd(c.normal_z, normal_z, hn::MulAdd(c.normal_y, normal_y, hn::Mul(c.normal_x, normal_x)));
    const auto accepted = hn::And(hn::Eq(id, c.id), hn::Ge(cos_angle, cos_threshold));
    VF du = hn::Sub(u, c.u), dv = hn::Sub(v, c.v), dn = hn::Zero(d);
    if (Sheared) {
        dn = hn::Sub(n, c.n);
        du = hn::NegMulAdd(c.shear_u, dn, du);
        dv = hn::NegMulAdd(c.shear_v, dn, dv);
    }
    // The negated coefficients -1 / (2 sigma^2).
    VF exponent = anisotropic ? hn::MulAdd(hn::Mul(du, du), c.neg_inv_two_sigma_sq,
                                           hn::Mul(hn::Mul(dv, dv), c.neg_inv_two_sigma_sq_v))
                              : hn::Mul(hn::MulAdd(du, du, hn::Mul(dv, dv)), c.neg_inv_two_sigma_sq);
    if (Sheared) exponent = hn::NegMulAdd(hn::Mul(dn, dn), c.inv_two_sigma_sq_n, exponent);
    return hn::IfThenElseZero(accepted, gather_exp_nonpositive(d, exponent));
}

/// Adds kLanes taps from index `t` into the partial sums of block `b`;
/// with `Tail`, only the lanes in `active`.
template <int K, bool Sheared, bool Tail>
HWY_INLINE void accumulate(const TapPlanes &g, const float *const *source, std::size_t t, const Centre &c,
                           hn::Mask<D> active, V (&sum)[K][kBlocks], V (&weight_sum)[kBlocks], int b) {
    const D d;
    const V weight = tap_weight<Sheared>(d, c, c.cos_threshold, c.anisotropic, hn::LoadU(d, g.normal_x + t),
                                         hn::LoadU(d, g.normal_y + t), hn::LoadU(d, g.normal_z + t),
                                         hn::LoadU(d, g.id + t), hn::LoadU(d, g.u + t), hn::LoadU(d, g.v + t),
                                         Sheared ? hn::LoadU(d, g.n + t) : hn::Zero(d));
    if (Tail) {
        weight_sum[b] = hn::IfThenElse(active, hn::Add(weight_sum[b], weight), weight_sum[b]);
        for (int k = 0; k < K; ++k)
            sum[k][b] =
                hn::IfThenElse(active, hn::MulAdd(weight, hn::LoadU(d, source[k] + t), sum[k][b]), sum[k][b]);
    } else {
        weight_sum[b] = hn::Add(weight_sum[b], weight);
        for (int k = 0; k < K; ++k) sum[k][b] = hn::MulAdd(weight, hn::LoadU(d, source[k] + t), sum[k][b]);
    }
}

/// Pixel `c`'s guides, broadcast to every lane.
template <bool Sheared>
HWY_INLINE Centre make_centre(const GatherGuides &g, std::size_t c, float cos_threshold) {
    const D d;
    Centre centre;
    centre.u = hn::Set(d, g.coord_u_m[c]);
    centre.v = hn::Set(d, g.coord_v_m[c]);
    centre.n = hn::Set(d, Sheared ? g.coord_n_m[c] : 0.0f);
    centre.shear_u = hn::Set(d, Sheared ? g.shear_u[c] : 0.0f);
    centre.shear_v = hn::Set(d, Sheared ? g.shear_v[c] : 0.0f);
    centre.inv_two_sigma_sq_n = hn::Set(d, Sheared ? g.inv_two_sigma_sq_n[c] : 0.0f);
    centre.normal_x = hn::Set(d, g.normal_x[c]);
    centre.normal_y = hn::Set(d, g.normal_y[c]);
    centre.normal_z = hn::Set(d, g.normal_z[c]);
    centre.id = hn::Set(d, g.object_id[c]);
    centre.neg_inv_two_sigma_sq = hn::Set(d, -g.inv_two_sigma_sq[c]);
    centre.anisotropic = g.anisotropic();
    centre.neg_inv_two_sigma_sq_v = hn::Set(d, centre.anisotropic ? -g.inv_two_sigma_sq_v[c] : 0.0f);
    centre.cos_threshold = hn::Set(d, cos_threshold);
    return centre;
}

/// gather.cpp's gather_pixel for an unmodulated sweep: pixel (x, y) over
/// taps |ox| <= reach_x, |oy| <= reach_y.
template <int K, bool Sheared>
void gather_pixel(const GatherSweep &s, int x, int y, int reach_x, int reach_y) {
    const D d;
    const GatherGuides &g = *s.guides;
    const std::size_t c = g.index(x, y);
    const float normal_x = g.normal_x[c], normal_y = g.normal_y[c], normal_z = g.normal_z[c],
                id = g.object_id[c];
    const Centre centre = make_centre<Sheared>(g, c, s.cos_threshold);
    const TapPlanes planes{g.coord_u_m.data(), g.coord_v_m.data(), Sheared ? g.coord_n_m.data() : nullptr,
                           g.normal_x.data(),  g.normal_y.data(),  g.normal_z.data(),
                           g.object_id.data()};
    const int x_begin = std::max(0, x - reach_x), x_end = std::min(g.width, x + reach_x + 1);
    const int y_begin = std::max(0, y - reach_y), y_end = std::min(g.height, y + reach_y + 1);

    V sum[K][kBlocks], weight_sum[kBlocks];
    for (int b = 0; b < kBlocks; ++b) {
        weight_sum[b] = hn::Zero(d);
        for (int k = 0; k < K; ++k) sum[k][b] = hn::Zero(d);
    }
    const auto all = hn::FirstN(d, kLanes);
    // A row's last taps (fewer than kSums) go to sums 0, 1, ...; at the
    // planes' very end they are copied into zero-padded buffers first, so no
    // load reads past a plane.
    const std::size_t plane_size = std::size_t(g.width) * std::size_t(g.height);
    alignas(64) float tail[7 + kMaxGatherChannels][kSums];
    const TapPlanes tail_planes{tail[0], tail[1], tail[2], tail[3], tail[4], tail[5], tail[6]};
    const float *tail_source[kMaxGatherChannels] = {tail[7], tail[8], tail[9], tail[10]};
    for (int ty = y_begin; ty < y_end; ++ty) {
        const std::size_t row = std::size_t(ty) * std::size_t(g.width);
        int tx = x_begin;
        for (; tx + kSums <= x_end; tx += kSums)
            for (int b = 0; b < kBlocks; ++b)
                accumulate<K, Sheared, false>(planes, s.source, row + std::size_t(tx + b * kLanes), centre,
                                              all, sum, weight_sum, b);
        const int rest = x_end - tx;
        if (rest == 0) continue;
        const std::size_t first = row + std::size_t(tx);
        if (first + kSums <= plane_size) {
            // Loads past the row's end stay inside the planes; those lanes are masked out.
            for (int b = 0; b * kLanes < rest; ++b)
                accumulate<K, Sheared, true>(planes, s.source, first + std::size_t(b * kLanes), centre,
                                             hn::FirstN(d, std::size_t(rest - b * kLanes)), sum, weight_sum,
                                             b);
            continue;
        }
        const float *from[7] = {planes.u,        planes.v,        planes.n, planes.normal_x,
                                planes.normal_y, planes.normal_z, planes.id};
        for (int p = 0; p < 7; ++p)
            for (int i = 0; i < kSums; ++i) tail[p][i] = from[p] && i < rest ? from[p][first + i] : 0.0f;
        for (int k = 0; k < K; ++k)
            for (int i = 0; i < kSums; ++i) tail[7 + k][i] = i < rest ? s.source[k][first + i] : 0.0f;
        for (int b = 0; b * kLanes < rest; ++b)
            accumulate<K, Sheared, true>(tail_planes, tail_source, std::size_t(b * kLanes), centre,
                                         hn::FirstN(d, std::size_t(rest - b * kLanes)), sum, weight_sum, b);
    }
    alignas(64) float lanes[K + 1][kSums];
    for (int b = 0; b < kBlocks; ++b) {
        hn::Store(weight_sum[b], d, lanes[K] + b * kLanes);
        for (int k = 0; k < K; ++k) hn::Store(sum[k][b], d, lanes[k] + b * kLanes);
    }
    float total[K] = {}, total_weight = 0;
    for (int lane = 0; lane < kSums; ++lane) {
        for (int k = 0; k < K; ++k) total[k] += lanes[k][lane];
        total_weight += lanes[K][lane];
    }
    // The centre always counts: a NaN or zero normal fails its own test, so
    // it is added back with weight 1.
    const bool centre_counted =
        (normal_x * normal_x + normal_y * normal_y + normal_z * normal_z) >= s.cos_threshold && id == id;
    if (!centre_counted) {
        for (int k = 0; k < K; ++k) total[k] += s.source[k][c];
        total_weight += 1.0f;
    }
    for (int k = 0; k < K; ++k) s.output[k][c] = total[k] / total_weight;
}

/// The 1D sweeps' vectors: the full native width. Each lane is its own
/// pixel, so the lane count changes no bit (unlike the 2D gather's kSums).
using DW = hn::ScalableTag<float>;
using DWI = hn::RebindToSigned<DW>;
using VW = hn::Vec<DW>;
constexpr int kWideLanes = int(HWY_LANES(float));

/// Lanes' worth of floats from `plane` at element `index` (may be negative
/// or run past `size`): a plain load inside the plane, else through a
/// zero-padded copy (the plane's first and last pixels).
HWY_INLINE VW load_guarded(const float *plane, std::ptrdiff_t index, std::ptrdiff_t size) {
    const DW d;
    if (HWY_LIKELY(index >= 0 && index + kWideLanes <= size)) return hn::LoadU(d, plane + index);
    alignas(64) float padded[kWideLanes];
    for (int i = 0; i < kWideLanes; ++i)
        padded[i] = index + i >= 0 && index + i < size ? plane[index + i] : 0.0f;
    return hn::Load(d, padded);
}

/// What the kWideLanes centre pixels of one vector compare their taps with.
struct WideCentres {
    VW u, v, n, shear_u, shear_v, inv_two_sigma_sq_n, normal_x, normal_y, normal_z, id;
    VW neg_inv_two_sigma_sq, neg_inv_two_sigma_sq_v;  ///< as Centre's
    hn::Vec<DWI> reach, x;
    std::ptrdiff_t c0 = 0;  ///< the first centre's index in the planes
};

/// The guides of the kWideLanes centres from index `c0`, with their reach and columns.
template <bool Sheared>
HWY_INLINE WideCentres load_wide_centres(const GatherGuides &g, std::ptrdiff_t c0, hn::Vec<DWI> reach,
                                         hn::Vec<DWI> lane_x) {
    const DW d;
    const std::ptrdiff_t size = std::ptrdiff_t(g.width) * g.height;
    WideCentres c;
    c.c0 = c0;
    c.u = load_guarded(g.coord_u_m.data(), c0, size);
    c.v = load_guarded(g.coord_v_m.data(), c0, size);
    c.n = Sheared ? load_guarded(g.coord_n_m.data(), c0, size) : hn::Zero(d);
    c.shear_u = Sheared ? load_guarded(g.shear_u.data(), c0, size) : hn::Zero(d);
    c.shear_v = Sheared ? load_guarded(g.shear_v.data(), c0, size) : hn::Zero(d);
    c.inv_two_sigma_sq_n = Sheared ? load_guarded(g.inv_two_sigma_sq_n.data(), c0, size) : hn::Zero(d);
    c.normal_x = load_guarded(g.normal_x.data(), c0, size);
    c.normal_y = load_guarded(g.normal_y.data(), c0, size);
    c.normal_z = load_guarded(g.normal_z.data(), c0, size);
    c.id = load_guarded(g.object_id.data(), c0, size);
    c.neg_inv_two_sigma_sq = hn::Neg(load_guarded(g.inv_two_sigma_sq.data(), c0, size));
    c.neg_inv_two_sigma_sq_v =
        g.anisotropic() ? hn::Neg(load_guarded(g.inv_two_sigma_sq_v.data(), c0, size)) : hn::Zero(d);
    c.reach = reach;
    c.x = lane_x;
    return c;
}

/// Adds the taps at offsets o_begin..o_end of the centres `c` into their
/// sums, in that order. Without `Guarded` every tap vector must lie inside
/// the planes (then no load checks its bounds).
template <int K, bool Sheared, bool AlongY, bool Guarded>
HWY_INLINE void add_taps(const GatherSweep &s, const WideCentres &c, int o_begin, int o_end, VW (&sum)[K],
                         VW &weight_sum) {
    const DW d;
    const DWI di;
    const GatherGuides &g = *s.guides;
    const std::ptrdiff_t size = std::ptrdiff_t(g.width) * g.height;
    const std::ptrdiff_t step = AlongY ? std::ptrdiff_t(g.width) : 1;  // between neighbouring taps
    auto load = [size, d](const float *plane, std::ptrdiff_t index) HWY_ATTR {
        return Guarded ? load_guarded(plane, index, size) : hn::LoadU(d, plane + index);
    };
    const float *const normal_x = g.normal_x.data(), *const normal_y = g.normal_y.data(),
                       *const normal_z = g.normal_z.data(), *const id = g.object_id.data(),
                       *const coord_u = g.coord_u_m.data(), *const coord_v = g.coord_v_m.data(),
                       *const coord_n = Sheared ? g.coord_n_m.data() : nullptr;
    const VW cos_threshold = hn::Set(d, s.cos_threshold);
    const bool anisotropic = g.anisotropic(), clip_x = !AlongY && !s.symmetric_borders;
    for (int o = o_begin; o <= o_end; ++o) {
        // |o| <= reach (and along x 0 <= x + o < width), lane by lane;
        // with symmetric borders reach <= min(x, width - 1 - x) implies the latter.
        auto inside = hn::Gt(c.reach, hn::Set(di, (o < 0 ? -o : o) - 1));
        if (clip_x) {
            const auto x_tap = hn::Add(c.x, hn::Set(di, o));
            inside =
                hn::And(inside, hn::And(hn::Gt(x_tap, hn::Set(di, -1)), hn::Lt(x_tap, hn::Set(di, g.width))));
        }
        const auto active = hn::RebindMask(d, inside);
        const std::ptrdiff_t t = c.c0 + std::ptrdiff_t(o) * step;
        const VW weight = tap_weight<Sheared>(
            d, c, cos_threshold, anisotropic, load(normal_x, t), load(normal_y, t), load(normal_z, t),
            load(id, t), load(coord_u, t), load(coord_v, t), Sheared ? load(coord_n, t) : hn::Zero(d));
        weight_sum = hn::IfThenElse(active, hn::Add(weight_sum, weight), weight_sum);
        for (int k = 0; k < K; ++k)
            sum[k] = hn::IfThenElse(active, hn::MulAdd(weight, load(s.source[k], t), sum[k]), sum[k]);
    }
}

/// Pixels [x_begin, x_end) of row `y` of a 1D sweep (both passes of the
/// separable gather), along x or, with `AlongY`, along y: kWideLanes
/// neighbouring centre pixels per vector, one lane each, all walking the same tap offsets (along y:
/// rows y + o, loaded contiguously, so no transpose is needed). Each pixel's
/// sums run over its taps from left to right (top to bottom), one add at a
/// time, so neither the lane count nor the threads change a bit, and along y
/// the bits are those of the along-x sweep over the transposed image.
template <int K, bool Sheared, bool AlongY>
void gather_row_along(const GatherSweep &s, int y, int x_begin, int x_end) {
    const DW d;
    const DWI di;
    const GatherGuides &g = *s.guides;
    const std::ptrdiff_t size = std::ptrdiff_t(g.width) * g.height, row = std::ptrdiff_t(y) * g.width;
    const std::ptrdiff_t step = AlongY ? std::ptrdiff_t(g.width) : 1;  // between neighbouring taps
    const VW cos_threshold = hn::Set(d, s.cos_threshold), one = hn::Set(d, 1.0f);
    const auto lane_offsets = hn::Iota(di, 0);
    for (int x0 = x_begin; x0 < x_end; x0 += kWideLanes) {
        const std::ptrdiff_t c0 = row + x0;
        const int lanes = std::min(kWideLanes, x_end - x0);  // centres in this vector
        // Each lane's reach: its radius, cut at the image's edges as
        // gather_row_k cuts it; -1 (no taps) for radius 0 and past the range.
        const std::int32_t *const radius_px = g.radius_px.data() + c0;
        auto radius = hn::Zero(di);
        if (lanes == kWideLanes) {
            radius = hn::LoadU(di, radius_px);
        } else {  // a loop, not std::copy_n: GCC makes that a slow `rep movs`
            alignas(64) std::int32_t radius_lanes[kWideLanes] = {};
            for (int i = 0; i < lanes; ++i) radius_lanes[i] = radius_px[i];
            radius = hn::Load(di, radius_lanes);
        }
        const auto lane_x = hn::Add(lane_offsets, hn::Set(di, x0));
        auto cut = radius;
        if (s.symmetric_borders)
            cut = AlongY ? hn::Min(cut, hn::Set(di, std::min(y, g.height - 1 - y)))
                         : hn::Min(cut, hn::Min(lane_x, hn::Sub(hn::Set(di, g.width - 1), lane_x)));
        const auto filtered = hn::And(hn::Lt(lane_x, hn::Set(di, x0 + lanes)), hn::Ne(radius, hn::Zero(di)));
        const auto reach = hn::IfThenElse(filtered, cut, hn::Set(di, -1));
        const int widest = hn::GetLane(hn::MaxOfLanes(di, reach));
        // The centres' own values: the output where a lane has no taps.
        VW centre_source[K];
        for (int k = 0; k < K; ++k) centre_source[k] = load_guarded(s.source[k], c0, size);
        VW out[K];
        if (widest < 0) {
            for (int k = 0; k < K; ++k) out[k] = centre_source[k];
        } else {
            const WideCentres c = load_wide_centres<Sheared>(g, c0, reach, lane_x);
            VW sum[K], weight_sum = hn::Zero(d);
            for (int k = 0; k < K; ++k) sum[k] = hn::Zero(d);
            // Along y the taps' rows are shared by all lanes: 0 <= y + o < height.
            const int o_begin = AlongY ? std::max(-widest, -y) : -widest;
            const int o_end = AlongY ? std::min(widest, g.height - 1 - y) : widest;
            // Away from the planes' first and last pixels no tap vector needs its bounds checked.
            const std::ptrdiff_t first = c0 + std::ptrdiff_t(o_begin) * step,
                                 last = c0 + std::ptrdiff_t(o_end) * step + kWideLanes;
            if (first >= 0 && last <= size)
                add_taps<K, Sheared, AlongY, false>(s, c, o_begin, o_end, sum, weight_sum);
            else
                add_taps<K, Sheared, AlongY, true>(s, c, o_begin, o_end, sum, weight_sum);
            // The centre always counts: a NaN or zero normal fails its own
            // test (nor does a NaN id match itself), so it is added back with weight 1.
            const VW length_sq =
                hn::Add(hn::Add(hn::Mul(c.normal_x, c.normal_x), hn::Mul(c.normal_y, c.normal_y)),
                        hn::Mul(c.normal_z, c.normal_z));
            const auto uncounted = hn::Not(hn::And(hn::Ge(length_sq, cos_threshold), hn::Eq(c.id, c.id)));
            const VW total_weight = hn::Add(weight_sum, hn::IfThenElseZero(uncounted, one));
            const auto keeps_value = hn::RebindMask(d, hn::Lt(reach, hn::Zero(di)));
            for (int k = 0; k < K; ++k) {
                const VW total = hn::IfThenElse(uncounted, hn::Add(sum[k], centre_source[k]), sum[k]);
                out[k] = hn::IfThenElse(keeps_value, centre_source[k], hn::Div(total, total_weight));
            }
        }
        for (int k = 0; k < K; ++k) {
            if (lanes == kWideLanes) {
                hn::StoreU(out[k], d, s.output[k] + c0);
                continue;
            }
            alignas(64) float stored[kWideLanes];
            hn::Store(out[k], d, stored);
            for (int i = 0; i < lanes; ++i) s.output[k][c0 + i] = stored[i];
        }
    }
}

template <int K, bool Sheared>
void gather_row_k(const GatherSweep &s, int y, int x_begin, int x_end) {
    if (s.along_x && !s.along_y) return gather_row_along<K, Sheared, false>(s, y, x_begin, x_end);
    if (s.along_y && !s.along_x) return gather_row_along<K, Sheared, true>(s, y, x_begin, x_end);
    const GatherGuides &g = *s.guides;
    for (int x = x_begin; x < x_end; ++x) {
        const std::size_t c = g.index(x, y);
        const int radius = g.radius_px[c];
        if (radius == 0) {
            for (int k = 0; k < K; ++k) s.output[k][c] = s.source[k][c];
            continue;
        }
        int reach_x = s.along_x ? radius : 0, reach_y = s.along_y ? radius : 0;
        if (s.symmetric_borders) {
            // gather.cpp: a window cut by an edge is cut on the other side too.
            reach_x = std::min({reach_x, x, g.width - 1 - x});
            reach_y = std::min({reach_y, y, g.height - 1 - y});
        }
        gather_pixel<K, Sheared>(s, x, y, reach_x, reach_y);
    }
}

template <bool Sheared>
void gather_row_sheared(const GatherSweep &s, int y, int x_begin, int x_end) {
    switch (s.channels) {
        case 1:
            return gather_row_k<1, Sheared>(s, y, x_begin, x_end);
        case 2:
            return gather_row_k<2, Sheared>(s, y, x_begin, x_end);
        case 3:
            return gather_row_k<3, Sheared>(s, y, x_begin, x_end);
        default:
            return gather_row_k<4, Sheared>(s, y, x_begin, x_end);
    }
}

const char *GatherRowTarget() {
    return hwy::TargetName(HWY_TARGET);
}

bool GatherRowFuses() {
    return HWY_NATIVE_FMA != 0;
}

void GatherRow(const GatherSweep &s, int y, int x_begin, int x_end) {
    x_begin = std::max(x_begin, 0);
    x_end = std::min(x_end, s.guides->width);
    if (x_begin >= x_end) return;
    if (s.guides->sheared())
        gather_row_sheared<true>(s, y, x_begin, x_end);
    else
        gather_row_sheared<false>(s, y, x_begin, x_end);
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/parallel.h"

namespace aaf::detail {

HWY_EXPORT(GatherRow);
HWY_EXPORT(GatherRowTarget);
HWY_EXPORT(GatherRowFuses);

void gather_row(const GatherSweep &sweep, int y, int x_begin, int x_end) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(GatherRow)(sweep, y, x_begin, x_end);
}

void gather_row(const GatherSweep &sweep, int y) {
    gather_row(sweep, y, 0, sweep.guides->width);
}

void gather_rows_tiled(const GatherSweep &sweep) {
    const int width = sweep.guides->width, height = sweep.guides->height;
    // Along x a row's taps are its own pixels: whole rows. So are narrow images,
    // whose window of rows already fits the cache.
    if (!sweep.along_y || width <= 2 * kGatherStripPixels) {
        parallel_for_rows(height, [&](int y) { gather_row(sweep, y); });
        return;
    }
    const int strips = (width + kGatherStripPixels - 1) / kGatherStripPixels;
    // Tiles of at most kGatherTileRows rows by one strip: a thread walks its
    // tile's rows within one strip.
    parallel_for_tiles(height, kGatherTileRows, strips, 1, [&](const TileRange &tile) {
        for (int strip = tile.col_begin; strip != tile.col_end; ++strip)
            for (int y = tile.row_begin; y != tile.row_end; ++y)
                gather_row(sweep, y, strip * kGatherStripPixels, (strip + 1) * kGatherStripPixels);
    });
}

const char *gather_row_target() {
    (void)instruction_set();
    return HWY_DYNAMIC_DISPATCH(GatherRowTarget)();
}

bool gather_row_fuses() {
    (void)instruction_set();
    return HWY_DYNAMIC_DISPATCH(GatherRowFuses)();
}

}  // namespace aaf::detail
#endif
