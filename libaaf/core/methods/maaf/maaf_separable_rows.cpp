// The separable MAAF passes over a line, an image row or column (maaf_separable_rows.h), for every
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

#include "aaf/core/kernels/vector_math-inl.h"
#include "aaf/core/methods/maaf/maaf_accumulation.h"

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

/// What a vector of centres compares its taps with, and their kernels.
struct Centres {
    V u, v, normal_x, normal_y, normal_z, id, cos_threshold;
    V inv_two_sigma_sq[kMaafMaxPairs], omega[kMaafMaxPairs], radius[kMaafMaxPairs];
    int widest = 0;  ///< the largest reach of any lane, pixels
    /// Per term, the largest reach max(radius_p, radius_q) of any lane: past it
    /// the term's weight is 0 in every lane and adds nothing (from +0, adding
    /// +-0 changes no sum's bits), so it is skipped.
    int term_reach[kMaafMaxTerms] = {};

    /// Centres i .. i + lanes - 1 of `line`; their guides are the taps at offset 0.
    Centres(D d, const MaafTerms &t, const MaafLine &line, std::size_t i) {
        const float *g = line.guides + std::size_t(line.margin) + i;
        const std::size_t gs = line.guide_stride;
        u = hn::LoadU(d, g);
        v = hn::LoadU(d, g + gs);
        normal_x = hn::LoadU(d, g + 2 * gs);
        normal_y = hn::LoadU(d, g + 3 * gs);
        normal_z = hn::LoadU(d, g + 4 * gs);
        id = hn::LoadU(d, g + 5 * gs);
        cos_threshold = hn::Set(d, t.cos_threshold);
        const float *k = line.kernels + i;
        const std::size_t ks = line.kernel_stride, pairs = std::size_t(t.pairs);
        for (std::size_t p = 0; p < pairs; ++p) {
            inv_two_sigma_sq[p] = hn::LoadU(d, k + p * ks);
            omega[p] = hn::LoadU(d, k + (pairs + p) * ks);
            radius[p] = hn::LoadU(d, k + (2 * pairs + p) * ks);
        }
        for (std::size_t lane = 0; lane < hn::Lanes(d); ++lane) {
            widest = std::max(widest, int(k[3 * pairs * ks + lane]));
            for (int j = 0; j < t.terms; ++j)
                term_reach[j] =
                    std::max(term_reach[j], int(std::max(k[(2 * pairs + std::size_t(t.pu[j])) * ks + lane],
                                                         k[(2 * pairs + std::size_t(t.pv[j])) * ks + lane])));
        }
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
/// The phase factors e^{j C_x^p du} are shared by every term with p on that
/// axis. Term j's weight goes to weights[2 j lanes] (re) and the next vector (im).
HWY_INLINE void term_weights(D d, const MaafTerms &f, const Centres &c, const Tap &t, float *weights) {
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
        if (t.offset_px > c.term_reach[j]) continue;  // not read (the passes skip the term)
        const int pu = f.pu[j], pv = f.pv[j];
        const V a = cos_u[pu], b = sin_u[pu], cv = cos_v[pv];
        const V dq = f.sign_v[j] < 0 ? hn::Neg(sin_v[pv]) : sin_v[pv];
        const M reached = hn::And(accepted, hn::Le(offset, hn::Max(c.radius[pu], c.radius[pv])));
        // Selects, not products: a rejected tap's weight is 0 whatever its guides held.
        const V g = hn::Mul(gauss_u[pu], gauss_v[pv]);
        float *w = weights + 2 * std::size_t(j) * hn::Lanes(d);
        hn::Store(hn::IfThenElseZero(reached, hn::Mul(g, hn::Sub(hn::Mul(a, cv), hn::Mul(b, dq)))), d, w);
        hn::Store(hn::IfThenElseZero(reached, hn::Mul(g, hn::Add(hn::Mul(a, dq), hn::Mul(b, cv)))), d,
                  w + hn::Lanes(d));
    }
}

/// a * b - c * e (or + for `add`), each product and the sum rounded on its own.
HWY_INLINE V complex_part(V a, V b, V c, V e, bool add) {
    return add ? hn::Add(hn::Mul(a, b), hn::Mul(c, e)) : hn::Sub(hn::Mul(a, b), hn::Mul(c, e));
}

/// Term j's sums for a vector of centres over its taps |offset| <= reach,
/// in order of offset, in registers: complex weight times complex source,
/// or its real part only. `weights` holds every tap's (term_weights, tap
/// offset -widest first); `src` is the term's first source array at the centres.
HWY_INLINE void term_sums(D d, const MaafTerms &f, const MaafLine &line, const float *weights, int widest,
                          std::size_t j, int reach, const float *src, bool complex, V *sums) {
    const std::size_t lanes = hn::Lanes(d), terms = std::size_t(f.terms), ss = line.source_stride;
    const float *value_re = src + j * ss, *value_im = src + (terms + j) * ss;
    const float *unoccluded_re = src + (2 * terms + j) * ss, *unoccluded_im = src + (3 * terms + j) * ss;
    V sum0 = hn::Zero(d), sum1 = hn::Zero(d), sum2 = hn::Zero(d), sum3 = hn::Zero(d);
    for (int offset = -reach; offset <= reach; ++offset) {
        const float *w = weights + (std::size_t(offset + widest) * terms + j) * 2 * lanes;
        const V re = hn::Load(d, w), im = hn::Load(d, w + lanes);
        const std::ptrdiff_t t = offset;
        const V v_re = hn::LoadU(d, value_re + t), v_im = hn::LoadU(d, value_im + t);
        const V u_re = hn::LoadU(d, unoccluded_re + t), u_im = hn::LoadU(d, unoccluded_im + t);
        sum0 = hn::Add(sum0, complex_part(re, v_re, im, v_im, false));
        if (complex) {
            sum1 = hn::Add(sum1, complex_part(re, v_im, im, v_re, true));
            sum2 = hn::Add(sum2, complex_part(re, u_re, im, u_im, false));
            sum3 = hn::Add(sum3, complex_part(re, u_im, im, u_re, true));
        } else {
            sum1 = hn::Add(sum1, complex_part(re, u_re, im, u_im, false));
        }
    }
    sums[0] = sum0;
    sums[1] = sum1;
    sums[2] = sum2;
    sums[3] = sum3;
}

/// Stores output q of a vector of centres; a lane of a complex pass whose
/// largest reach is 0 keeps its own source (`keeps`).
HWY_INLINE void store_output(D d, const MaafLine &line, std::size_t i, std::size_t q, V value,
                             hn::Mask<D> keeps) {
    const float *own = line.sources + std::size_t(line.margin) + i + q * line.source_stride;
    value = hn::IfThenElse(keeps, hn::LoadU(d, own), value);
    float *dst = line.out + i * line.out_centre_step + q * line.out_plane_step;
    if (line.out_centre_step == 1) {
        hn::StoreU(value, d, dst);
        return;
    }
    HWY_ALIGN float lane_values[kMaafLinePadding];  // centres down a column: one output row each
    hn::Store(value, d, lane_values);
    for (std::size_t lane = 0; lane < hn::Lanes(d); ++lane)
        dst[lane * line.out_centre_step] = lane_values[lane];
}

void LinePass(const MaafTerms &f, const MaafLine &line, bool complex) {
    const D d;
    const std::size_t lanes = hn::Lanes(d), terms = std::size_t(f.terms), gs = line.guide_stride;
    // Every tap's weights for one vector of centres: at most 2 margin + 1 taps.
    hwy::AlignedFreeUniquePtr<float[]> buffer =
        hwy::AllocateAligned<float>((2 * std::size_t(line.margin) + 1) * terms * 2 * lanes);
    float *weights = buffer.get();
    for (std::size_t i = 0; i < std::size_t(line.count); i += lanes) {
        const Centres c(d, f, line, i);
        for (int offset = -c.widest; offset <= c.widest; ++offset) {
            const float *g =
                line.guides + std::size_t(std::ptrdiff_t(line.margin) + std::ptrdiff_t(i) + offset);
            const Tap tap{hn::LoadU(d, g),          hn::LoadU(d, g + gs),     hn::LoadU(d, g + 2 * gs),
                          hn::LoadU(d, g + 3 * gs), hn::LoadU(d, g + 4 * gs), hn::LoadU(d, g + 5 * gs),
                          std::abs(offset)};
            term_weights(d, f, c, tap, weights + std::size_t(offset + c.widest) * terms * 2 * lanes);
        }
        const hn::Mask<D> keeps =
            complex ? hn::Eq(hn::LoadU(d, line.kernels + 3 * std::size_t(f.pairs) * line.kernel_stride + i),
                             hn::Zero(d))
                    : hn::FirstN(d, 0);
        const float *src = line.sources + std::size_t(line.margin) + i;
        V sums[4];
        for (std::size_t j = 0; j < terms; ++j) {
            // Past its reach a term's weight is 0 in every lane: its taps stop there (from +0, adding
            // +-0 changes no sum's bits). A centre that filters nothing has reach 0: its own tap.
            term_sums(d, f, line, weights, c.widest, j, std::min(c.term_reach[j], c.widest), src, complex,
                      sums);
            for (std::size_t part = 0; part < (complex ? 4u : 2u); ++part)
                store_output(d, line, i, part * terms + j, sums[part], keeps);
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "aaf/core/util/instruction_set.h"

namespace aaf::detail {

HWY_EXPORT(LinePass);

void maaf_line_pass(const MaafTerms &terms, const MaafLine &line, bool complex) {
    (void)instruction_set();  // applies AAF_ISA before the first dispatch
    HWY_DYNAMIC_DISPATCH(LinePass)(terms, line, complex);
}

}  // namespace aaf::detail
#endif
