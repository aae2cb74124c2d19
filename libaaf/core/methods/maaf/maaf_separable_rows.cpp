// The separable MAAF passes over a row (maaf_separable_rows.h) for every
// instruction set Google Highway targets, chosen at run time: a vector of
// centres at a time, each lane its own centre with its own kernels and its
// own sums in tap order. Compiled without contraction (CMakeLists.txt) and
// written with plain multiplies and adds, so every lane computes the same
// operations as every other instruction set's lanes: the same bits.
#include "aaf/core/methods/maaf/maaf_separable_rows.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

// Arrays of vectors need sized vector types: no scalable (SVE, RVV) targets.
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "methods/maaf/maaf_separable_rows.cpp"
#include <hwy/aligned_allocator.h>
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "aaf/core/methods/maaf/maaf_accumulation.h"

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

/// fast_exp_nonpositive (fast_exp.h) with round-to-nearest by the 1.5 * 2^23
/// shift: exp(x) for x <= 0, relative error below 3e-7, a multiply then an
/// add at every step (never fused), so each lane gives the same bits on every target.
HWY_INLINE V exp_nonpositive(D d, V x) {
    const DI di;
    const V clamped = hn::Min(hn::Max(x, hn::Set(d, -87.0f)), hn::Zero(d));  // Max(NaN, -87) is -87
    const V rounding_shift = hn::Set(d, 12582912.0f);                        // 1.5 * 2^23
    const V shifted = hn::Add(hn::Mul(clamped, hn::Set(d, 1.44269504088896341f)), rounding_shift);
    const V k = hn::Sub(shifted, rounding_shift);  // exact: an integer in [-126, 0]
    const V r = hn::Sub(hn::Sub(clamped, hn::Mul(k, hn::Set(d, 0.693145751953125f))),
                        hn::Mul(k, hn::Set(d, 1.428606765330187045e-06f)));
    V p = hn::Set(d, 1.0f / 720.0f);  // Taylor, as fast_exp_nonpositive
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f / 120.0f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f / 24.0f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f / 6.0f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 0.5f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f));
    p = hn::Add(hn::Mul(p, r), hn::Set(d, 1.0f));
    // 2^k through the exponent bits: shifted's bits are those of 1.5 * 2^23 plus k.
    const V scale =
        hn::BitCast(d, hn::ShiftLeft<23>(hn::Sub(hn::BitCast(di, shifted), hn::Set(di, 0x4B400000 - 127))));
    return hn::Mul(p, scale);
}

/// sin and cos of x: x = q pi/2 + r with q rounded to nearest (the 1.5 * 2^23
/// shift) and pi/2 split in three (Cody and Waite, Cephes' constants, q pi/2's
/// first part exact up to |q| = 2^16), Cephes' sinf/cosf polynomials on
/// |r| <= pi/4, then the quadrant's swap and signs. Absolute error about
/// 1e-7 for the phases here (|x| well under 1e4 radians); |x| is clamped to
/// 2^20 so that no input gives a non-finite value.
HWY_INLINE void sin_cos(D d, V x, V &sin_x, V &cos_x) {
    const DI di;
    const V limit = hn::Set(d, 1048576.0f);
    x = hn::Min(hn::Max(x, hn::Neg(limit)), limit);
    const V rounding_shift = hn::Set(d, 12582912.0f);
    const V shifted = hn::Add(hn::Mul(x, hn::Set(d, 0.636619772367581343f)), rounding_shift);  // 2 / pi
    const V q = hn::Sub(shifted, rounding_shift);
    V r = hn::Sub(x, hn::Mul(q, hn::Set(d, 1.5703125f)));
    r = hn::Sub(r, hn::Mul(q, hn::Set(d, 4.837512969970703125e-4f)));
    r = hn::Sub(r, hn::Mul(q, hn::Set(d, 7.54978995489188216e-8f)));
    const V z = hn::Mul(r, r);
    V s = hn::Set(d, -1.9515295891e-4f);
    s = hn::Add(hn::Mul(s, z), hn::Set(d, 8.3321608736e-3f));
    s = hn::Add(hn::Mul(s, z), hn::Set(d, -1.6666654611e-1f));
    s = hn::Add(hn::Mul(hn::Mul(s, z), r), r);
    V c = hn::Set(d, 2.443315711809948e-5f);
    c = hn::Add(hn::Mul(c, z), hn::Set(d, -1.388731625493765e-3f));
    c = hn::Add(hn::Mul(c, z), hn::Set(d, 4.166664568298827e-2f));
    c = hn::Add(hn::Sub(hn::Mul(hn::Mul(c, z), z), hn::Mul(hn::Set(d, 0.5f), z)), hn::Set(d, 1.0f));
    // The quadrant q mod 4 from shifted's low bits: sin, cos = (s, c), (c, -s), (-s, -c), (-c, s).
    const auto quadrant = hn::BitCast(di, shifted);
    const M swap = hn::RebindMask(d, hn::Ne(hn::And(quadrant, hn::Set(di, 1)), hn::Zero(di)));
    const M negate_sin = hn::RebindMask(d, hn::Ne(hn::And(quadrant, hn::Set(di, 2)), hn::Zero(di)));
    const M negate_cos =
        hn::RebindMask(d, hn::Ne(hn::And(hn::Add(quadrant, hn::Set(di, 1)), hn::Set(di, 2)), hn::Zero(di)));
    const V sin_r = hn::IfThenElse(swap, c, s), cos_r = hn::IfThenElse(swap, s, c);
    sin_x = hn::IfThenElse(negate_sin, hn::Neg(sin_r), sin_r);
    cos_x = hn::IfThenElse(negate_cos, hn::Neg(cos_r), cos_r);
}

/// What a vector of centres compares its taps with, and their kernels.
struct Centres {
    V u, v, normal_x, normal_y, normal_z, id, cos_threshold;
    V inv_two_sigma_sq[kMaafMaxPairs], omega[kMaafMaxPairs], radius[kMaafMaxPairs];
    int widest = 0;  ///< the largest reach of any lane, pixels

    Centres(D d, const MaafSeparableFrame &f, std::size_t i) {
        u = hn::LoadU(d, f.coord_u + i);
        v = hn::LoadU(d, f.coord_v + i);
        normal_x = hn::LoadU(d, f.normal_x + i);
        normal_y = hn::LoadU(d, f.normal_y + i);
        normal_z = hn::LoadU(d, f.normal_z + i);
        id = hn::LoadU(d, f.object_id + i);
        cos_threshold = hn::Set(d, f.cos_threshold);
        const std::size_t plane = std::size_t(f.stride) * std::size_t(f.height);
        for (int p = 0; p < f.pairs; ++p) {
            inv_two_sigma_sq[p] = hn::LoadU(d, f.inv_two_sigma_sq + std::size_t(p) * plane + i);
            omega[p] = hn::LoadU(d, f.omega + std::size_t(p) * plane + i);
            radius[p] = hn::LoadU(d, f.radius_px + std::size_t(p) * plane + i);
        }
        for (std::size_t lane = 0; lane < hn::Lanes(d); ++lane)
            widest = std::max(widest, int(f.widest_px[i + lane]));
    }
};

/// One tap's guides for a vector of centres.
struct Tap {
    V u, v, normal_x, normal_y, normal_z, id;
    int offset_px;  ///< |tap - centre| along the pass
};

/// Every term's weight g_p(du) g_q(dv) e^{j (C_x^p du + sign_v C_x^q dv)}
/// (MAAF Eq. 12, 13) for one tap, 0 where gather() rejects the tap or the
/// term's reach max(radius_p, radius_q) is below the tap's offset.
/// The phase factors e^{j C_x^p du} are shared by every term with p on that axis.
HWY_INLINE void term_weights(D d, const MaafSeparableFrame &f, const Centres &c, const Tap &t, V *re, V *im) {
    M accepted = hn::FirstN(d, hn::Lanes(d));  // the centre itself always counts
    if (t.offset_px != 0) {
        const V cos_angle = hn::Add(hn::Add(hn::Mul(c.normal_x, t.normal_x), hn::Mul(c.normal_y, t.normal_y)),
                                    hn::Mul(c.normal_z, t.normal_z));
        accepted = hn::And(hn::Eq(t.id, c.id), hn::Ge(cos_angle, c.cos_threshold));
    }
    const V du = hn::Sub(t.u, c.u), dv = hn::Sub(t.v, c.v);
    const V neg_du_sq = hn::Mul(hn::Neg(du), du), neg_dv_sq = hn::Mul(hn::Neg(dv), dv);
    V gauss_u[kMaafMaxPairs], gauss_v[kMaafMaxPairs];
    V cos_u[kMaafMaxPairs], sin_u[kMaafMaxPairs], cos_v[kMaafMaxPairs], sin_v[kMaafMaxPairs];
    for (int p = 0; p < f.pairs; ++p) {
        gauss_u[p] = exp_nonpositive(d, hn::Mul(neg_du_sq, c.inv_two_sigma_sq[p]));
        gauss_v[p] = exp_nonpositive(d, hn::Mul(neg_dv_sq, c.inv_two_sigma_sq[p]));
    }
    cos_u[0] = cos_v[0] = hn::Set(d, 1.0f);
    sin_u[0] = sin_v[0] = hn::Zero(d);
    for (int p = 1; p < f.pairs; ++p) {
        sin_cos(d, hn::Mul(c.omega[p], du), sin_u[p], cos_u[p]);
        sin_cos(d, hn::Mul(c.omega[p], dv), sin_v[p], cos_v[p]);
    }
    const V offset = hn::Set(d, float(t.offset_px));
    for (int j = 0; j < f.terms; ++j) {
        const int pu = f.term_pu[j], pv = f.term_pv[j];
        const V a = cos_u[pu], b = sin_u[pu], cv = cos_v[pv];
        const V dq = f.term_sign_v[j] < 0 ? hn::Neg(sin_v[pv]) : sin_v[pv];
        const M reached = hn::And(accepted, hn::Le(offset, hn::Max(c.radius[pu], c.radius[pv])));
        // Selects, not products: a rejected tap's weight is 0 whatever its guides held.
        const V g = hn::Mul(gauss_u[pu], gauss_v[pv]);
        re[j] = hn::IfThenElseZero(reached, hn::Mul(g, hn::Sub(hn::Mul(a, cv), hn::Mul(b, dq))));
        im[j] = hn::IfThenElseZero(reached, hn::Mul(g, hn::Add(hn::Mul(a, dq), hn::Mul(b, cv))));
    }
}

/// Scratch for one row: the sums of a vector of centres, one vector per plane.
struct RowScratch {
    hwy::AlignedFreeUniquePtr<float[]> sums;
    RowScratch(D d, int terms) : sums(hwy::AllocateAligned<float>(4 * std::size_t(terms) * hn::Lanes(d))) {}
};

void VerticalRow(const MaafSeparableFrame &f, int y, float *out, MaafPaddedRow row) {
    const D d;
    const std::size_t lanes = hn::Lanes(d), stride = std::size_t(f.stride);
    const std::size_t plane = stride * std::size_t(f.height), planes = 4 * std::size_t(f.terms);
    RowScratch scratch(d, f.terms);
    float *sums = scratch.sums.get();
    V re[kMaafMaxTerms], im[kMaafMaxTerms];
    for (std::size_t x = 0; x < stride; x += lanes) {
        const std::size_t centre = std::size_t(y) * stride + x;
        const Centres c(d, f, centre);
        float *dst = out + std::size_t(row.margin) + x;
        if (c.widest == 0) {  // no lane filtered: every centre keeps its sources
            for (std::size_t q = 0; q < planes; ++q)
                hn::StoreU(hn::LoadU(d, f.sources + q * plane + centre), d,
                           dst + q * std::size_t(row.length));
            continue;
        }
        for (std::size_t q = 0; q < planes; ++q) hn::Store(hn::Zero(d), d, sums + q * lanes);
        const int first = std::max(0, y - c.widest), last = std::min(f.height - 1, y + c.widest);
        for (int ty = first; ty <= last; ++ty) {
            const std::size_t t = std::size_t(ty) * stride + x;
            const Tap tap{hn::LoadU(d, f.coord_u + t),
                          hn::LoadU(d, f.coord_v + t),
                          hn::LoadU(d, f.normal_x + t),
                          hn::LoadU(d, f.normal_y + t),
                          hn::LoadU(d, f.normal_z + t),
                          hn::LoadU(d, f.object_id + t),
                          std::abs(ty - y)};
            term_weights(d, f, c, tap, re, im);
            const std::size_t terms = std::size_t(f.terms);
            for (std::size_t j = 0; j < terms; ++j) {  // complex weight times complex source
                const V value_re = hn::LoadU(d, f.sources + j * plane + t);
                const V value_im = hn::LoadU(d, f.sources + (terms + j) * plane + t);
                const V unoccluded_re = hn::LoadU(d, f.sources + (2 * terms + j) * plane + t);
                const V unoccluded_im = hn::LoadU(d, f.sources + (3 * terms + j) * plane + t);
                float *s = sums + j * lanes;
                const std::size_t block = terms * lanes;
                hn::Store(
                    hn::Add(hn::Load(d, s), hn::Sub(hn::Mul(re[j], value_re), hn::Mul(im[j], value_im))), d,
                    s);
                hn::Store(hn::Add(hn::Load(d, s + block),
                                  hn::Add(hn::Mul(re[j], value_im), hn::Mul(im[j], value_re))),
                          d, s + block);
                hn::Store(hn::Add(hn::Load(d, s + 2 * block),
                                  hn::Sub(hn::Mul(re[j], unoccluded_re), hn::Mul(im[j], unoccluded_im))),
                          d, s + 2 * block);
                hn::Store(hn::Add(hn::Load(d, s + 3 * block),
                                  hn::Add(hn::Mul(re[j], unoccluded_im), hn::Mul(im[j], unoccluded_re))),
                          d, s + 3 * block);
            }
        }
        // A lane whose own widest reach is 0 keeps its sources, as a lane of an unfiltered vector.
        const M keeps = hn::Eq(hn::LoadU(d, f.widest_px + centre), hn::Zero(d));
        for (std::size_t q = 0; q < planes; ++q)
            hn::StoreU(hn::IfThenElse(keeps, hn::LoadU(d, f.sources + q * plane + centre),
                                      hn::Load(d, sums + q * lanes)),
                       d, dst + q * std::size_t(row.length));
    }
}

void HorizontalRow(const MaafSeparableFrame &f, int y, const float *in, const float *guides,
                   MaafPaddedRow row, float *out) {
    const D d;
    const std::size_t lanes = hn::Lanes(d), stride = std::size_t(f.stride), terms = std::size_t(f.terms);
    const std::size_t length = std::size_t(row.length);
    const float *g_u = guides, *g_v = guides + length, *g_nx = guides + 2 * length,
                *g_ny = guides + 3 * length, *g_nz = guides + 4 * length, *g_id = guides + 5 * length;
    RowScratch scratch(d, f.terms);
    float *sums = scratch.sums.get();
    V re[kMaafMaxTerms], im[kMaafMaxTerms];
    for (std::size_t x = 0; x < stride; x += lanes) {
        const Centres c(d, f, std::size_t(y) * stride + x);
        for (std::size_t q = 0; q < 2 * terms; ++q) hn::Store(hn::Zero(d), d, sums + q * lanes);
        for (int offset = -c.widest; offset <= c.widest; ++offset) {
            const std::size_t t = std::size_t(std::ptrdiff_t(row.margin) + std::ptrdiff_t(x) + offset);
            const Tap tap{hn::LoadU(d, g_u + t),  hn::LoadU(d, g_v + t),  hn::LoadU(d, g_nx + t),
                          hn::LoadU(d, g_ny + t), hn::LoadU(d, g_nz + t), hn::LoadU(d, g_id + t),
                          std::abs(offset)};
            term_weights(d, f, c, tap, re, im);
            for (std::size_t j = 0; j < terms; ++j) {  // real parts only
                const V value_re = hn::LoadU(d, in + j * length + t);
                const V value_im = hn::LoadU(d, in + (terms + j) * length + t);
                const V unoccluded_re = hn::LoadU(d, in + (2 * terms + j) * length + t);
                const V unoccluded_im = hn::LoadU(d, in + (3 * terms + j) * length + t);
                float *s = sums + j * lanes;
                hn::Store(
                    hn::Add(hn::Load(d, s), hn::Sub(hn::Mul(re[j], value_re), hn::Mul(im[j], value_im))), d,
                    s);
                float *s_u = sums + (terms + j) * lanes;
                hn::Store(hn::Add(hn::Load(d, s_u),
                                  hn::Sub(hn::Mul(re[j], unoccluded_re), hn::Mul(im[j], unoccluded_im))),
                          d, s_u);
            }
        }
        for (std::size_t q = 0; q < 2 * terms; ++q)
            hn::StoreU(hn::Load(d, sums + q * lanes), d, out + q * stride + x);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(VerticalRow);
HWY_EXPORT(HorizontalRow);

void maaf_vertical_row(const MaafSeparableFrame &frame, int y, float *out, MaafPaddedRow row) {
    (void)instruction_set();  // applies AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(VerticalRow)(frame, y, out, row);
}

void maaf_horizontal_row(const MaafSeparableFrame &frame, int y, const float *in, const float *guides,
                         MaafPaddedRow row, float *sums) {
    (void)instruction_set();
    HWY_DYNAMIC_DISPATCH(HorizontalRow)(frame, y, in, guides, row, sums);
}

}  // namespace aaf::detail
#endif
