// AAF's separable gather sweeps (aaf_gather_rows.h) for every instruction
// set Google Highway targets, chosen at run time. Every multiply and add is
// its own operation (no MulAdd, and -ffp-contract=off in CMakeLists.txt):
// Highway's MulAdd fuses on AVX2 and AVX-512 but not on SSE4, so only
// unfused arithmetic gives one set of bits on all of them.
#include "aaf/core/methods/aaf/aaf_gather_rows.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>

#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/aaf/aaf_gather_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "aaf/core/kernels/vector_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using VI = hn::Vec<DI>;
using M = hn::Mask<D>;
constexpr int kLanes = int(HWY_LANES(float));

/// Lanes' worth of `plane` from element `index` (may be negative or run past
/// `size`): a plain load inside the plane, else through a zero-padded copy.
template <class DT, typename T>
HWY_INLINE hn::Vec<DT> load_guarded(DT d, const T *plane, std::ptrdiff_t index, std::ptrdiff_t size) {
    if (HWY_LIKELY(index >= 0 && index + kLanes <= size)) return hn::LoadU(d, plane + index);
    alignas(64) T padded[kLanes];
    for (int i = 0; i < kLanes; ++i) padded[i] = index + i >= 0 && index + i < size ? plane[index + i] : T(0);
    return hn::Load(d, padded);
}

/// What the kLanes centre pixels of one vector compare their taps with.
struct Centres {
    V u, v, n, shear_u, shear_v, normal_x, normal_y, normal_z, id;
    /// -log2(e) / (2 beta^2) along u, v and n: the exponent in base 2, so
    /// the tap's exponential needs no scaling.
    V coef_u, coef_v, coef_n;
    VI reach, x;
    std::ptrdiff_t c0 = 0;  ///< the first centre's index in the planes
};

/// -log2(e) * inv_two_sigma_sq, held above -FLT_MAX so that 0 times it stays 0.
HWY_INLINE V base2_coefficient(const float *plane, std::ptrdiff_t c0, std::ptrdiff_t size) {
    const D d;
    const V scaled = hn::Mul(load_guarded(d, plane, c0, size), hn::Set(d, -1.44269504088896341f));
    return hn::Max(scaled, hn::Set(d, -std::numeric_limits<float>::max()));
}

template <bool Sheared>
HWY_INLINE Centres load_centres(const GatherGuides &g, std::ptrdiff_t c0, VI reach, VI lane_x) {
    const D d;
    const std::ptrdiff_t size = std::ptrdiff_t(g.width) * g.height;
    Centres c;
    c.c0 = c0;
    c.u = load_guarded(d, g.coord_u_m.data(), c0, size);
    c.v = load_guarded(d, g.coord_v_m.data(), c0, size);
    c.n = Sheared ? load_guarded(d, g.coord_n_m.data(), c0, size) : hn::Zero(d);
    c.shear_u = Sheared ? load_guarded(d, g.shear_u.data(), c0, size) : hn::Zero(d);
    c.shear_v = Sheared ? load_guarded(d, g.shear_v.data(), c0, size) : hn::Zero(d);
    c.normal_x = load_guarded(d, g.normal_x.data(), c0, size);
    c.normal_y = load_guarded(d, g.normal_y.data(), c0, size);
    c.normal_z = load_guarded(d, g.normal_z.data(), c0, size);
    c.id = load_guarded(d, g.object_id.data(), c0, size);
    c.coef_u = base2_coefficient(g.inv_two_sigma_sq.data(), c0, size);
    c.coef_v = g.anisotropic() ? base2_coefficient(g.inv_two_sigma_sq_v.data(), c0, size) : c.coef_u;
    c.coef_n = Sheared ? base2_coefficient(g.inv_two_sigma_sq_n.data(), c0, size) : hn::Zero(d);
    c.reach = reach;
    c.x = lane_x;
    return c;
}

/// Adds the taps at offsets o_begin..o_end of the centres `c` into their
/// sums, in that order. Without `Guarded` every tap vector lies inside the
/// planes; with `Uniform` every lane's taps share its id and normal
/// (Centres' uniform reach), so the tests are skipped; without `Masked`
/// every offset is within every lane's reach (and row). The same bits.
template <int K, bool Sheared, bool AlongY, bool Guarded, bool Uniform, bool Masked = true>
HWY_INLINE void add_taps(const AafSweep &s, const Centres &c, int o_begin, int o_end, V (&sum)[K],
                         V &weight_sum) {
    const D d;
    const DI di;
    const GatherGuides &g = *s.guides;
    const std::ptrdiff_t size = std::ptrdiff_t(g.width) * g.height;
    const std::ptrdiff_t step = AlongY ? std::ptrdiff_t(g.width) : 1;  // between neighbouring taps
    auto load = [size, d](const float *plane, std::ptrdiff_t index) HWY_ATTR {
        return Guarded ? load_guarded(d, plane, index, size) : hn::LoadU(d, plane + index);
    };
    const V cos_threshold = hn::Set(d, s.cos_threshold);
    const bool anisotropic = g.anisotropic(), clip_x = !AlongY && !s.symmetric_borders;
    for (int o = o_begin; o <= o_end; ++o) {
        // |o| <= reach (and along x 0 <= x + o < width), lane by lane;
        // with symmetric borders reach <= min(x, width - 1 - x) implies the latter.
        auto inside = hn::Gt(c.reach, hn::Set(di, (o < 0 ? -o : o) - 1));
        if (!Masked) inside = hn::FirstN(di, kLanes);
        if (Masked && clip_x) {
            const VI x_tap = hn::Add(c.x, hn::Set(di, o));
            inside =
                hn::And(inside, hn::And(hn::Gt(x_tap, hn::Set(di, -1)), hn::Lt(x_tap, hn::Set(di, g.width))));
        }
        const M active = hn::RebindMask(d, inside);
        const std::ptrdiff_t t = c.c0 + std::ptrdiff_t(o) * step;
        M kept = active;
        if (!Uniform) {
            // AAF Sec. 6: the same object, and normals within the threshold.
            const V cos_angle = hn::Add(hn::Add(hn::Mul(c.normal_x, load(g.normal_x.data(), t)),
                                                hn::Mul(c.normal_y, load(g.normal_y.data(), t))),
                                        hn::Mul(c.normal_z, load(g.normal_z.data(), t)));
            kept = hn::And(
                kept, hn::And(hn::Eq(load(g.object_id.data(), t), c.id), hn::Ge(cos_angle, cos_threshold)));
        }
        V du = hn::Sub(load(g.coord_u_m.data(), t), c.u), dv = hn::Sub(load(g.coord_v_m.data(), t), c.v);
        V dn = hn::Zero(d);
        if (Sheared) {  // GatherGuides::shear_u/v: slid along the centre's direction onto its plane
            dn = hn::Sub(load(g.coord_n_m.data(), t), c.n);
            du = hn::Sub(du, hn::Mul(c.shear_u, dn));
            dv = hn::Sub(dv, hn::Mul(c.shear_v, dn));
        }
        // AAF Eq. 11-12 in base 2: -log2(e) (du^2 + dv^2) / (2 beta^2), per light axis when anisotropic.
        V exponent = anisotropic
                         ? hn::Add(hn::Mul(hn::Mul(du, du), c.coef_u), hn::Mul(hn::Mul(dv, dv), c.coef_v))
                         : hn::Mul(hn::Add(hn::Mul(du, du), hn::Mul(dv, dv)), c.coef_u);
        if (Sheared) exponent = hn::Add(exponent, hn::Mul(hn::Mul(dn, dn), c.coef_n));
        const V weight = Masked || !Uniform ? hn::IfThenElseZero(kept, exp2_nonpositive(d, exponent))
                                            : exp2_nonpositive(d, exponent);
        weight_sum = hn::Add(weight_sum, weight);
        for (int k = 0; k < K; ++k) {
            const V added = hn::Add(sum[k], hn::Mul(weight, load(s.source[k], t)));
            sum[k] = Masked ? hn::IfThenElse(active, added, sum[k]) : added;
        }
    }
}

/// The taps of the centres `c` over offsets o_begin..o_end, in that order:
/// the unchecked loads where every tap vector lies inside the planes, the
/// tests skipped where every lane's uniform reach covers its own, and no
/// masks over the offsets every lane takes (|o| <= the narrowest reach).
template <int K, bool Sheared, bool AlongY>
HWY_INLINE void add_all_taps(const AafSweep &s, const Centres &c, int x0, int o_begin, int o_end,
                             int narrowest, bool uniform, V (&sum)[K], V &weight_sum) {
    const GatherGuides &g = *s.guides;
    const std::ptrdiff_t size = std::ptrdiff_t(g.width) * g.height;
    const std::ptrdiff_t step = AlongY ? std::ptrdiff_t(g.width) : 1;
    const bool inner =
        c.c0 + std::ptrdiff_t(o_begin) * step >= 0 && c.c0 + std::ptrdiff_t(o_end) * step + kLanes <= size;
    if (!inner) {
        if (uniform) return add_taps<K, Sheared, AlongY, true, true>(s, c, o_begin, o_end, sum, weight_sum);
        return add_taps<K, Sheared, AlongY, true, false>(s, c, o_begin, o_end, sum, weight_sum);
    }
    int low = std::max(o_begin, -narrowest), high = std::min(o_end, narrowest);
    if (!AlongY && !s.symmetric_borders) {  // every lane's taps inside the row too
        low = std::max(low, -x0);
        high = std::min(high, g.width - x0 - kLanes);
    }
    if (low > high) {  // no offset all lanes take: all masked
        low = o_end + 1;
        high = o_end;
    }
    if (uniform) {
        add_taps<K, Sheared, AlongY, false, true>(s, c, o_begin, low - 1, sum, weight_sum);
        add_taps<K, Sheared, AlongY, false, true, false>(s, c, low, high, sum, weight_sum);
        return add_taps<K, Sheared, AlongY, false, true>(s, c, high + 1, o_end, sum, weight_sum);
    }
    add_taps<K, Sheared, AlongY, false, false>(s, c, o_begin, low - 1, sum, weight_sum);
    add_taps<K, Sheared, AlongY, false, false, false>(s, c, low, high, sum, weight_sum);
    add_taps<K, Sheared, AlongY, false, false>(s, c, high + 1, o_end, sum, weight_sum);
}

/// Each lane's reach for the kLanes centres from column x0 of row y: its
/// radius, cut at the image's edges with symmetric borders; -1 (no taps)
/// for radius 0 and past the `lanes` centres.
template <bool AlongY>
HWY_INLINE VI lane_reach(const AafSweep &s, int y, int x0, int lanes, VI lane_x) {
    const DI di;
    const GatherGuides &g = *s.guides;
    const std::int32_t *const radius_px = g.radius_px.data() + std::ptrdiff_t(y) * g.width + x0;
    VI radius = hn::Zero(di);
    if (lanes == kLanes) {
        radius = hn::LoadU(di, radius_px);
    } else {  // a loop, not std::copy_n: GCC makes that a slow `rep movs`
        alignas(64) std::int32_t radius_lanes[kLanes] = {};
        for (int i = 0; i < lanes; ++i) radius_lanes[i] = radius_px[i];
        radius = hn::Load(di, radius_lanes);
    }
    VI cut = radius;
    if (s.symmetric_borders)
        cut = AlongY ? hn::Min(cut, hn::Set(di, std::min(y, g.height - 1 - y)))
                     : hn::Min(cut, hn::Min(lane_x, hn::Sub(hn::Set(di, g.width - 1), lane_x)));
    const auto filtered = hn::And(hn::Lt(lane_x, hn::Set(di, x0 + lanes)), hn::Ne(radius, hn::Zero(di)));
    return hn::IfThenElse(filtered, cut, hn::Set(di, -1));
}

/// Writes the first `lanes` lanes of `value` to `plane` from `index`.
HWY_INLINE void store_lanes(V value, float *plane, std::ptrdiff_t index, int lanes) {
    const D d;
    if (lanes == kLanes) return hn::StoreU(value, d, plane + index);
    alignas(64) float stored[kLanes];
    hn::Store(value, d, stored);
    for (int i = 0; i < lanes; ++i) plane[index + i] = stored[i];
}

/// Whether pixel c passes its own object and normal tests as a tap of
/// itself, with add_taps' arithmetic: (nx nx + ny ny) + nz nz.
HWY_INLINE bool passes_own_tests(const GatherGuides &g, std::ptrdiff_t c, float cos_threshold) {
    const float nx = g.normal_x[std::size_t(c)], ny = g.normal_y[std::size_t(c)],
                nz = g.normal_z[std::size_t(c)];
    const float id = g.object_id[std::size_t(c)];
    return (nx * nx + ny * ny) + nz * nz >= cos_threshold && id == id;
}

/// The lanes where a pixel has the object id and normal of its neighbour
/// `offset` pixels before it. Equal normals differ at most in the sign of a
/// zero, which changes no test: the dot product of the two is the pixel's
/// own, or its zero of the other sign.
HWY_INLINE M same_surface_lanes(const GatherGuides &g, std::ptrdiff_t i, std::ptrdiff_t offset) {
    const D d;
    auto same = [&](const float *plane)
                    HWY_ATTR { return hn::Eq(hn::LoadU(d, plane + i), hn::LoadU(d, plane + i - offset)); };
    return hn::And(hn::And(same(g.object_id.data()), same(g.normal_x.data())),
                   hn::And(same(g.normal_y.data()), same(g.normal_z.data())));
}

/// same_surface_lanes() of two pixels, one at a time.
HWY_INLINE bool same_surface(const GatherGuides &g, std::ptrdiff_t a, std::ptrdiff_t b) {
    const std::size_t i = std::size_t(a), j = std::size_t(b);
    return g.object_id[i] == g.object_id[j] && g.normal_x[i] == g.normal_x[j] &&
           g.normal_y[i] == g.normal_y[j] && g.normal_z[i] == g.normal_z[j];
}

/// Whether pixels [begin, end) of one row all have pixel begin's id and
/// normal, and it passes its own tests: then so does every tap among them.
HWY_INLINE bool uniform_span(const GatherGuides &g, std::ptrdiff_t begin, std::ptrdiff_t end,
                             float cos_threshold) {
    const D d;
    if (!passes_own_tests(g, begin, cos_threshold)) return false;
    if (end - begin < kLanes) {
        for (std::ptrdiff_t i = begin + 1; i < end; ++i)
            if (!same_surface(g, i, begin)) return false;
        return true;
    }
    // Each vector against the span's first pixel, the last one overlapping.
    const V id = hn::Set(d, g.object_id[std::size_t(begin)]), nx = hn::Set(d, g.normal_x[std::size_t(begin)]),
            ny = hn::Set(d, g.normal_y[std::size_t(begin)]), nz = hn::Set(d, g.normal_z[std::size_t(begin)]);
    for (std::ptrdiff_t i = begin;; i = std::min(i + kLanes, end - kLanes)) {
        const M same = hn::And(hn::And(hn::Eq(hn::LoadU(d, g.object_id.data() + i), id),
                                       hn::Eq(hn::LoadU(d, g.normal_x.data() + i), nx)),
                               hn::And(hn::Eq(hn::LoadU(d, g.normal_y.data() + i), ny),
                                       hn::Eq(hn::LoadU(d, g.normal_z.data() + i), nz)));
        if (!hn::AllTrue(d, same)) return false;
        if (i + kLanes >= end) return true;
    }
}

/// Pixels [x_begin, x_end) of row `y`, along x or, with `AlongY`, along y
/// (rows y + o loaded contiguously: no transpose). Each lane's sums run
/// over its taps in order, so the lane count changes no bit.
template <int K, bool Sheared, bool AlongY>
void gather_row_along(const AafSweep &s, int y, int x_begin, int x_end) {
    const D d;
    const DI di;
    const GatherGuides &g = *s.guides;
    const std::ptrdiff_t size = std::ptrdiff_t(g.width) * g.height, row = std::ptrdiff_t(y) * g.width;
    const V cos_threshold = hn::Set(d, s.cos_threshold), one = hn::Set(d, 1.0f);
    for (int x0 = x_begin; x0 < x_end; x0 += kLanes) {
        const std::ptrdiff_t c0 = row + x0;
        const int lanes = std::min(kLanes, x_end - x0);  // centres in this vector
        const VI lane_x = hn::Add(hn::Iota(di, 0), hn::Set(di, x0));
        const VI reach = lane_reach<AlongY>(s, y, x0, lanes, lane_x);
        const int widest = hn::GetLane(hn::MaxOfLanes(di, reach));
        V centre_source[K], out[K];
        for (int k = 0; k < K; ++k) out[k] = centre_source[k] = load_guarded(d, s.source[k], c0, size);
        if (widest >= 0) {
            const Centres c = load_centres<Sheared>(g, c0, reach, lane_x);
            // The tests can be skipped where every tap shares its centre's id and normal.
            bool uniform;
            if (AlongY) {
                uniform = hn::AllFalse(di, hn::Lt(load_guarded(di, s.uniform_reach, c0, size), reach));
            } else {
                const std::ptrdiff_t first = row + std::max(0, x0 - widest);
                uniform =
                    uniform_span(g, first, row + std::min(g.width, x0 + lanes + widest), s.cos_threshold);
            }
            V sum[K], weight_sum = hn::Zero(d);
            for (int k = 0; k < K; ++k) sum[k] = hn::Zero(d);
            // Along y the taps' rows are shared by all lanes: 0 <= y + o < height.
            const int o_begin = AlongY ? std::max(-widest, -y) : -widest;
            const int o_end = AlongY ? std::min(widest, g.height - 1 - y) : widest;
            const int narrowest = hn::GetLane(hn::MinOfLanes(di, reach));
            add_all_taps<K, Sheared, AlongY>(s, c, x0, o_begin, o_end, narrowest, uniform, sum, weight_sum);
            // The centre always counts: a NaN or zero normal fails its own
            // test (nor does a NaN id match itself), so it is added back with weight 1.
            const V length_sq =
                hn::Add(hn::Add(hn::Mul(c.normal_x, c.normal_x), hn::Mul(c.normal_y, c.normal_y)),
                        hn::Mul(c.normal_z, c.normal_z));
            const M uncounted = hn::Not(hn::And(hn::Ge(length_sq, cos_threshold), hn::Eq(c.id, c.id)));
            const V total_weight = hn::Add(weight_sum, hn::IfThenElseZero(uncounted, one));
            const M keeps_value = hn::RebindMask(d, hn::Lt(reach, hn::Zero(di)));
            for (int k = 0; k < K; ++k) {
                const V total = hn::IfThenElse(uncounted, hn::Add(sum[k], centre_source[k]), sum[k]);
                out[k] = hn::IfThenElse(keeps_value, centre_source[k], hn::Div(total, total_weight));
            }
        }
        for (int k = 0; k < K; ++k) store_lanes(out[k], s.output[k], c0, lanes);
    }
}

/// AafUniformReachAlongY's step down one row (`Down`) or up, for the
/// kLanes columns from pixel i: the run of equal pixels before it, from the
/// run `next` of the pixel before.
HWY_INLINE VI run_after(const GatherGuides &g, std::ptrdiff_t i, std::ptrdiff_t offset, VI before) {
    const DI di;
    const VI longer = hn::Min(hn::Add(before, hn::Set(di, 1)), hn::Set(di, kUniformEndless));
    return hn::IfThenElseZero(hn::RebindMask(di, same_surface_lanes(g, i, offset)), longer);
}

void AafUniformReachAlongY(const GatherGuides &g, float cos_threshold, int x_begin, int x_end,
                           std::int32_t *reach) {
    const D d;
    const DI di;
    const std::ptrdiff_t width = g.width;
    const int vector_end = x_begin + (x_end - x_begin) / kLanes * kLanes;  // the rest one column at a time
    auto step = [&](std::int32_t before, std::ptrdiff_t i, std::ptrdiff_t offset) {
        return same_surface(g, i, i - offset) ? std::min(before + 1, kUniformEndless) : 0;
    };
    std::fill(reach + x_begin, reach + x_end, kUniformEndless);
    for (int y = 1; y < g.height; ++y) {
        const std::ptrdiff_t row = std::ptrdiff_t(y) * width;
        for (int x = x_begin; x < vector_end; x += kLanes)
            hn::StoreU(run_after(g, row + x, width, hn::LoadU(di, reach + row + x - width)), di,
                       reach + row + x);
        for (int x = vector_end; x < x_end; ++x)
            reach[row + x] = step(reach[row + x - width], row + x, width);
    }
    // Upwards: the run below each pixel, then the shorter of the two.
    std::vector<std::int32_t> below(std::size_t(x_end - x_begin), kUniformEndless);
    const V threshold = hn::Set(d, cos_threshold);
    for (int y = g.height - 1; y >= 0; --y) {
        const std::ptrdiff_t row = std::ptrdiff_t(y) * width;
        for (int x = x_begin; x < vector_end; x += kLanes) {
            const std::ptrdiff_t i = row + x;
            std::int32_t *const run = below.data() + (x - x_begin);
            const V nx = hn::LoadU(d, g.normal_x.data() + i), ny = hn::LoadU(d, g.normal_y.data() + i),
                    nz = hn::LoadU(d, g.normal_z.data() + i), id = hn::LoadU(d, g.object_id.data() + i);
            const M own = hn::And(
                hn::Ge(hn::Add(hn::Add(hn::Mul(nx, nx), hn::Mul(ny, ny)), hn::Mul(nz, nz)), threshold),
                hn::Eq(id, id));
            const VI shorter = hn::Min(hn::LoadU(di, reach + i), hn::LoadU(di, run));
            hn::StoreU(hn::IfThenElse(hn::RebindMask(di, own), shorter, hn::Set(di, -1)), di, reach + i);
            if (y > 0) hn::StoreU(run_after(g, i, width, hn::LoadU(di, run)), di, run);
        }
        for (int x = vector_end; x < x_end; ++x) {
            const std::ptrdiff_t i = row + x;
            std::int32_t &run = below[std::size_t(x - x_begin)];
            reach[i] = passes_own_tests(g, i, cos_threshold) ? std::min(reach[i], run) : -1;
            if (y > 0) run = step(run, i, width);
        }
    }
}

template <int K, bool Sheared>
void gather_row_k(const AafSweep &s, int y, int x_begin, int x_end) {
    if (s.along_y) return gather_row_along<K, Sheared, true>(s, y, x_begin, x_end);
    gather_row_along<K, Sheared, false>(s, y, x_begin, x_end);
}

template <bool Sheared>
void gather_row_sheared(const AafSweep &s, int y, int x_begin, int x_end) {
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

void AafGatherRow(const AafSweep &s, int y, int x_begin, int x_end) {
    x_begin = std::max(x_begin, 0);
    x_end = std::min(x_end, s.guides->width);
    if (x_begin >= x_end) return;
    if (s.guides->sheared())
        gather_row_sheared<true>(s, y, x_begin, x_end);
    else
        gather_row_sheared<false>(s, y, x_begin, x_end);
}

const char *AafGatherRowTarget() {
    return hwy::TargetName(HWY_TARGET);
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(AafGatherRow);
HWY_EXPORT(AafGatherRowTarget);
HWY_EXPORT(AafUniformReachAlongY);

void aaf_gather_row(const AafSweep &sweep, int y, int x_begin, int x_end) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(AafGatherRow)(sweep, y, x_begin, x_end);
}

void aaf_uniform_reach_along_y(const GatherGuides &guides, float cos_threshold, int x_begin, int x_end,
                               std::int32_t *reach) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(AafUniformReachAlongY)(guides, cos_threshold, x_begin, x_end, reach);
}

const char *aaf_gather_row_target() {
    (void)instruction_set();
    return HWY_DYNAMIC_DISPATCH(AafGatherRowTarget)();
}

}  // namespace aaf::detail
#endif
