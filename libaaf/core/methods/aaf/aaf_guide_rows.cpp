// aaf_gather_guides()' per-pixel step (aaf_guide_rows.h) for every
// instruction set Google Highway targets, chosen at run time. Each lane
// repeats the scalar definitions (aaf_bandlimits.cpp, and aaf_filter.cpp's
// former per-pixel loop, kept as the reference in test_aaf_guide_rows.cpp)
// operation for operation: std::min/max/clamp as the
// comparisons they are defined by (NaN picks the same operand), IEEE
// divides and square roots, and -ffp-contract=off (CMakeLists.txt) so no
// multiply-add is fused.
#include "aaf/core/methods/aaf/aaf_guide_rows.h"

#include "aaf/core/methods/aaf/aaf_params.h"

#include <cstdint>
#include <limits>

#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/aaf/aaf_guide_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;
constexpr int kMaxLanes = int(HWY_LANES(float));

/// std::max(a, b): (a < b) ? b : a.
HWY_INLINE V max_of(V a, V b) {
    return hn::IfThenElse(hn::Lt(a, b), b, a);
}
/// std::min(a, b): (b < a) ? b : a.
HWY_INLINE V min_of(V a, V b) {
    return hn::IfThenElse(hn::Lt(b, a), b, a);
}
/// dot(Vec3 a, Vec3 b) of vec3.h: (a.x b.x + a.y b.y) + a.z b.z.
HWY_INLINE V dot3(V ax, V ay, V az, V bx, V by, V bz) {
    return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

/// `count - i` (at most a vector's) floats of a row from index i, zeros past its end.
HWY_INLINE V load_row(const float *row, int i, int count) {
    const D d;
    if (HWY_LIKELY(i + kMaxLanes <= count)) return hn::LoadU(d, row + i);
    alignas(64) float lanes[kMaxLanes] = {};
    for (int l = 0; i + l < count; ++l) lanes[l] = row[i + l];
    return hn::Load(d, lanes);
}
template <typename T, class DT>
HWY_INLINE void store_row(DT d, hn::Vec<DT> v, T *row, int i, int count) {
    if (HWY_LIKELY(i + kMaxLanes <= count)) return hn::StoreU(v, d, row + i);
    alignas(64) T lanes[kMaxLanes];
    hn::Store(v, d, lanes);
    for (int l = 0; i + l < count; ++l) row[i + l] = lanes[l];
}

/// mu_free_bandlimits() of aaf_bandlimits.cpp (AAF Eq. 4, 6, 7, 8) for one light axis.
struct MuFree {
    V s1, omega_light, omega_x_max, omega_y_max, omega_x_f0;
};
HWY_INLINE MuFree mu_free(V d1, V d2_min, V d2_max, V pixel_size, float sigma_m, float alpha) {
    const D d;
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), alpha_v = hn::Set(d, alpha);
    MuFree b;
    b.s1 = max_of(zero, hn::Sub(hn::Div(d1, d2_min), one));        // AAF Eq. 4
    const V s2 = max_of(zero, hn::Sub(hn::Div(d1, d2_max), one));  // AAF Eq. 4
    b.omega_light = hn::Div(one, hn::Set(d, sigma_m));             // Sec. 4.1: Omega_L^max = 1/sigma
    const V omega_pixel = hn::Div(one, pixel_size);                // Sec. 4.1: Omega_pix^max = 1/d
    b.omega_x_max = hn::Mul(hn::Div(alpha_v, hn::Add(one, s2)), omega_pixel);  // AAF Eq. 6
    b.omega_y_max =
        hn::Mul(hn::Mul(alpha_v, max_of(zero, hn::Sub(one, hn::Div(d2_min, d1)))), omega_pixel);  // AAF Eq. 7
    // AAF Eq. 8, clipped to Omega_x^max where Omega_L / s2 is unbounded (s2 -> 0).
    const V light_induced = hn::IfThenElse(hn::Gt(s2, zero), hn::Div(b.omega_light, s2),
                                           hn::Set(d, std::numeric_limits<float>::infinity()));
    b.omega_x_f0 = min_of(light_induced, b.omega_x_max);
    return b;
}

/// samples_per_pixel_at() of aaf_bandlimits.cpp: AAF Eq. 15 at mu.
HWY_INLINE V samples_at(const MuFree &b, V mu, V pixel_size, float sigma_m) {
    const D d;
    const V omega_x_f = hn::Mul(mu, b.omega_x_f0);  // Sec. 5.2
    const V omega_x_star = hn::Add(omega_x_f, b.omega_x_max);
    const V omega_y_star = hn::Add(b.omega_light, min_of(hn::Mul(b.s1, omega_x_f), b.omega_y_max));
    const V pixel_term = hn::Mul(omega_x_star, pixel_size);
    const V light_term = hn::Mul(hn::Mul(omega_y_star, hn::Set(d, 2.0f)), hn::Set(d, sigma_m));
    return hn::Mul(hn::Mul(hn::Mul(pixel_term, pixel_term), light_term), light_term);
}

/// mu_for_samples() of aaf_bandlimits.cpp in the lanes of `needed`: the
/// same bisection, every lane stepping until its own interval is closed.
HWY_INLINE V mu_for_samples(const AafGuideConstants &c, M needed, V samples, V pixel_size, const MuFree &u,
                            const MuFree &v) {
    const D d;
    constexpr float kMaxMu = 1e4f;
    const bool square = !c.anisotropic;
    auto rate = [&](V mu) {
        const V rate_u = samples_at(u, mu, pixel_size, c.sigma_u_m);
        if (square) return rate_u;
        return hn::Mul(hn::Sqrt(rate_u), hn::Sqrt(samples_at(v, mu, pixel_size, c.sigma_v_m)));
    };
    const V floor_mu = hn::Set(d, c.mu), max_mu = hn::Set(d, kMaxMu);
    const M below_floor_rate = hn::Lt(rate(floor_mu), samples);
    const M at_max = hn::And(below_floor_rate, hn::Le(rate(max_mu), samples));
    M active = hn::AndNot(at_max, hn::And(needed, below_floor_rate));
    V low = floor_mu, high = max_mu;
    const V tolerance = hn::Set(d, 1e-4f);
    active = hn::And(active, hn::Gt(hn::Sub(high, low), hn::Mul(tolerance, low)));
    while (!hn::AllFalse(d, active)) {
        const V mid = hn::Sqrt(hn::Mul(low, high));  // geometric: mu spans decades
        const M below = hn::Lt(rate(mid), samples);
        low = hn::IfThenElse(hn::And(active, below), mid, low);
        high = hn::IfThenElse(hn::AndNot(below, active), mid, high);
        active = hn::And(active, hn::Gt(hn::Sub(high, low), hn::Mul(tolerance, low)));
    }
    return hn::IfThenElse(at_max, max_mu, low);  // low stays the floor where the floor's rate suffices
}

/// A point or direction per lane.
struct V3 {
    V x, y, z;
};
HWY_INLINE V3 broadcast3(const float (&a)[3]) {
    const D d;
    return {hn::Set(d, a[0]), hn::Set(d, a[1]), hn::Set(d, a[2])};
}
HWY_INLINE V3 load_row3(const float *const (&rows)[3], int i, int count) {
    return {load_row(rows[0], i, count), load_row(rows[1], i, count), load_row(rows[2], i, count)};
}
HWY_INLINE V3 sub3(const V3 &a, const V3 &b) {
    return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)};
}
HWY_INLINE V dot3(const V3 &a, const V3 &b) {
    return dot3(a.x, a.y, a.z, b.x, b.y, b.z);
}

/// The light's plane (AafGuideConstants) in every lane.
struct LightFrame {
    V3 center, axis_u, axis_v, normal;
};

/// The light's variance seen from each lane's pixel, along u and v.
struct Spread {
    V u_sq, v_sq;
};

/// The along-light guides of one vector of pixels (p their positions, n their
/// normals, rel = p - the light's centre): stores the shear and the coordinate
/// along the light's normal, and returns the light's spread at the pixel (0
/// where the tap does not slide).
HWY_INLINE Spread store_along_light_guides(const AafGuideConstants &c, const LightFrame &light, const V3 &p,
                                           const V3 &n, const V3 &rel, M usable,
                                           const AafGuideRowOutputs &out, int i, int count) {
    const D d;
    const V zero = hn::Zero(d);
    // Delta_eff = Delta - l (n . Delta) / (n . l), l the unit direction to the light's
    // centre: the tap slid along l onto the centre's plane parallel to the light
    // (AAF Fig. 2's geometry), of which AAF Eq. 12 is the case l = n.
    const V3 to = sub3(light.center, p);
    const V distance = hn::Sqrt(dot3(to, to));
    M slides = hn::Gt(distance, zero);
    if (c.guarded) {
        const V receiver_length = hn::Sqrt(dot3(n, n));
        const M projection_holds =
            hn::And(hn::Gt(receiver_length, zero),
                    hn::Ge(hn::Abs(dot3(n, light.normal)),
                           hn::Mul(hn::Set(d, kDegenerateProjectionCos), receiver_length)));
        slides = hn::AndNot(projection_holds, slides);
    }
    const V3 l{hn::Div(to.x, distance), hn::Div(to.y, distance), hn::Div(to.z, distance)};
    const V cos_light = dot3(l, light.normal);
    // Nearly edge-on (|n . l| < 0.05, 87 degrees) the shear is held at 20.
    const V min_cos = hn::Set(d, 0.05f);
    const V denominator =
        hn::IfThenElse(hn::Lt(hn::Abs(cos_light), min_cos), hn::CopySign(min_cos, cos_light), cos_light);
    const V shear_u = hn::Div(dot3(l, light.axis_u), denominator);
    const V shear_v = hn::Div(dot3(l, light.axis_v), denominator);
    const V coord_n = dot3(light.normal, rel);
    const V d1 = hn::Abs(coord_n);
    const V d1_sq = hn::Mul(d1, d1);
    const M sheared = hn::And(usable, slides);
    store_row(d, hn::IfThenElseZero(sheared, shear_u), out.shear_u, i, count);
    store_row(d, hn::IfThenElseZero(sheared, shear_v), out.shear_v, i, count);
    store_row(d, hn::IfThenElseZero(usable, coord_n), out.coord_n_m, i, count);
    return {hn::IfThenElseZero(sheared, hn::Div(hn::Set(d, c.variance_u_m2), d1_sq)),
            hn::IfThenElseZero(sheared, hn::Div(hn::Set(d, c.variance_v_m2), d1_sq))};
}

/// projected_pixel_size_m() of aaf_bandlimits.cpp, where the footprint is finite.
HWY_INLINE V projected_pixel_size(V pixel_size, const V3 &n, V normal_length, const V3 &light_normal) {
    const D d;
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    const M tilts =
        hn::And(hn::IsFinite(pixel_size), hn::And(hn::Gt(normal_length, zero), hn::IsFinite(normal_length)));
    const V cos_planes = hn::Div(hn::Abs(dot3(n, light_normal)), normal_length);
    // std::clamp(cos, lo, 1): (cos < lo) ? lo : (1 < cos) ? 1 : cos.
    const V lo = hn::Set(d, kDegenerateProjectionCos);
    const V clamped =
        hn::IfThenElse(hn::Lt(cos_planes, lo), lo, hn::IfThenElse(hn::Lt(one, cos_planes), one, cos_planes));
    return hn::IfThenElse(tilts, hn::Mul(pixel_size, clamped), pixel_size);
}

/// beta of AAF Eq. 13 along the light's two axes, in the lanes of `filtered`.
struct Beta {
    V u, v;
};
HWY_INLINE Beta beta_widths(const AafGuideConstants &c, const AafGuideRowInputs &in, int i, int count,
                            M filtered, V d1, V d2_min, V d2_max, V pixel_size) {
    const D d;
    if (c.fixed_beta_m > 0) return {hn::Set(d, c.fixed_beta_m), hn::Set(d, c.fixed_beta_m)};
    const V one = hn::Set(d, 1.0f);
    const MuFree bu = mu_free(d1, d2_min, d2_max, pixel_size, c.sigma_u_m, c.alpha);
    const MuFree bv = c.anisotropic ? mu_free(d1, d2_min, d2_max, pixel_size, c.sigma_v_m, c.alpha) : bu;
    V mu = hn::Set(d, c.mu);
    // AAF Sec. 5.2: the filter follows the samples actually taken.
    if (c.per_pixel_mu) mu = mu_for_samples(c, filtered, load_row(in.spp, i, count), pixel_size, bu, bv);
    // AAF Eq. 13: beta = 1 / (k Omega_x^f), Omega_x^f = mu Omega_x0^f (Sec. 5.2).
    const V k = hn::Set(d, c.k);
    const V beta_u = hn::Div(one, hn::Mul(k, hn::Mul(mu, bu.omega_x_f0)));
    return {beta_u, c.anisotropic ? hn::Div(one, hn::Mul(k, hn::Mul(mu, bv.omega_x_f0))) : beta_u};
}

/// Stores the filter's reach, beta and the Gaussian's 1 / (2 beta^2) weights
/// (0 outside `kept`) of one vector of filtered pixels.
HWY_INLINE void store_widths(const AafGuideConstants &c, const AafGuideRowOutputs &out, int i, int count,
                             M kept, const Beta &beta, V own_pixel_size, const Spread &spread) {
    const D d;
    const DI di;
    const V one = hn::Set(d, 1.0f), float_max = hn::Set(d, std::numeric_limits<float>::max());
    // beta is in world metres; the reach in pixels follows from the pixel's own footprint.
    const V widest = max_of(beta.u, beta.v);
    const V radius = min_of(hn::Ceil(hn::Div(hn::Mul(hn::Set(d, c.cutoff_sigmas), widest), own_pixel_size)),
                            hn::Set(d, c.max_radius_px));
    store_row(di, hn::ConvertTo(di, hn::IfThenElseZero(kept, radius)), out.radius_px, i, count);
    // The beta output: the isotropic width of the same area, sqrt(beta_u beta_v).
    const V isotropic = c.anisotropic ? hn::Sqrt(hn::Mul(beta.u, beta.v)) : beta.u;
    if (out.beta_m) store_row(d, hn::IfThenElseZero(kept, isotropic), out.beta_m, i, count);
    // 1 / (2 beta^2): a beta below ~1e-19 m squares to 0 or a denormal; the
    // largest float instead of inf keeps the centre tap's exponent 0 * that = 0.
    const V inv_u = min_of(hn::Div(one, hn::Mul(hn::Mul(hn::Set(d, 2.0f), beta.u), beta.u)), float_max);
    const V inv_v = c.anisotropic
                        ? min_of(hn::Div(one, hn::Mul(hn::Mul(hn::Set(d, 2.0f), beta.v), beta.v)), float_max)
                        : inv_u;
    store_row(d, hn::IfThenElseZero(kept, inv_u), out.inv_two_sigma_sq, i, count);
    if (c.anisotropic) store_row(d, hn::IfThenElseZero(kept, inv_v), out.inv_two_sigma_sq_v, i, count);
    if (c.along_light) {
        const V weight_n = hn::Add(hn::Mul(spread.u_sq, inv_u), hn::Mul(spread.v_sq, inv_v));
        const V inv_n = hn::IfThenElse(hn::IsFinite(weight_n), weight_n, float_max);
        store_row(d, hn::IfThenElseZero(kept, inv_n), out.inv_two_sigma_sq_n, i, count);
    }
}

/// Zero weights and reach for a vector of pixels AAF does not filter.
HWY_INLINE void store_unfiltered(const AafGuideConstants &c, const AafGuideRowOutputs &out, int i,
                                 int count) {
    const D d;
    const DI di;
    const V zero = hn::Zero(d);
    if (out.beta_m) store_row(d, zero, out.beta_m, i, count);
    store_row(d, zero, out.inv_two_sigma_sq, i, count);
    if (c.anisotropic) store_row(d, zero, out.inv_two_sigma_sq_v, i, count);
    if (c.along_light) store_row(d, zero, out.inv_two_sigma_sq_n, i, count);
    store_row(di, hn::Zero(di), out.radius_px, i, count);
}

void AafGuideRow(const AafGuideConstants &c, const AafGuideRowInputs &in, const AafGuideRowOutputs &out,
                 int count) {
    const D d;
    const V zero = hn::Zero(d);
    const LightFrame light{broadcast3(c.center), broadcast3(c.axis_u), broadcast3(c.axis_v),
                           broadcast3(c.light_normal)};
    for (int i = 0; i < count; i += kMaxLanes) {
        const V3 p = load_row3(in.position, i, count), n = load_row3(in.normal, i, count);
        const V id = load_row(in.object_id, i, count);
        // Coordinates along the light's two tangent axes (AAF Eq. 12 for the orthonormal frame).
        const V3 rel = sub3(p, light.center);
        const V u = dot3(light.axis_u, rel);
        const V v = dot3(light.axis_v, rel);
        // Unusable geometry: never a tap (NaN id), never filtered, every other guide 0.
        const M usable = hn::IsFinite(hn::Add(u, v));
        store_row(d, hn::IfThenElseZero(usable, u), out.coord_u_m, i, count);
        store_row(d, hn::IfThenElseZero(usable, v), out.coord_v_m, i, count);
        store_row(d, hn::IfThenElse(usable, id, hn::Set(d, std::numeric_limits<float>::quiet_NaN())),
                  out.object_id, i, count);

        Spread spread{zero, zero};
        if (c.along_light) spread = store_along_light_guides(c, light, p, n, rel, usable, out, i, count);
        const V normal_length = hn::Sqrt(dot3(n, n));
        const M unit_normal =
            hn::And(usable, hn::And(hn::Gt(normal_length, zero), hn::IsFinite(normal_length)));
        store_row(d, hn::IfThenElseZero(unit_normal, hn::Div(n.x, normal_length)), out.normal[0], i, count);
        store_row(d, hn::IfThenElseZero(unit_normal, hn::Div(n.y, normal_length)), out.normal[1], i, count);
        store_row(d, hn::IfThenElseZero(unit_normal, hn::Div(n.z, normal_length)), out.normal[2], i, count);

        // beta of AAF Eq. 13 along the light's axes, 0 where AAF does not filter.
        const V d1 = load_row(in.d1_m, i, count);
        const V own_pixel_size = load_row(in.pixel_size_m, i, count);
        const V pixel_size = c.projected_pixel
                                 ? projected_pixel_size(own_pixel_size, n, normal_length, light.normal)
                                 : own_pixel_size;
        const V d2_min = load_row(in.d2_min_m, i, count), d2_max = load_row(in.d2_max_m, i, count);
        const M has_occluder = hn::And(hn::Gt(d2_max, zero), hn::Lt(d2_max, hn::Set(d, 3.0e38f)));
        M filtered = hn::AndNot(hn::Eq(id, zero), usable);
        filtered = hn::And(filtered, hn::And(hn::Gt(d1, zero), hn::Gt(pixel_size, zero)));
        filtered = hn::And(filtered, hn::And(hn::IsFinite(pixel_size), has_occluder));
        if (hn::AllFalse(d, filtered)) {
            store_unfiltered(c, out, i, count);
            continue;
        }
        const Beta beta = beta_widths(c, in, i, count, filtered, d1, d2_min, d2_max, pixel_size);
        const M kept = hn::And(filtered, hn::And(hn::And(hn::Gt(beta.u, zero), hn::Gt(beta.v, zero)),
                                                 hn::And(hn::IsFinite(beta.u), hn::IsFinite(beta.v))));
        store_widths(c, out, i, count, kept, beta, own_pixel_size, spread);
    }
}

const char *AafGuideRowTarget() {
    return hwy::TargetName(HWY_TARGET);
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(AafGuideRow);
HWY_EXPORT(AafGuideRowTarget);

void aaf_guide_row(const AafGuideConstants &constants, const AafGuideRowInputs &in,
                   const AafGuideRowOutputs &out, int count) {
    (void)instruction_set();  // applies $AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(AafGuideRow)(constants, in, out, count);
}

const char *aaf_guide_row_target() {
    (void)instruction_set();
    return HWY_DYNAMIC_DISPATCH(AafGuideRowTarget)();
}

}  // namespace aaf::detail
#endif
