// Vector exp and sin/cos for the Highway kernels (included once per
// instruction set, Highway's -inl.h convention): written with plain
// multiplies and adds, never fused (the including file is compiled without
// contraction), so each lane gives the same bits on every instruction set.
#if defined(AAF_CORE_KERNELS_VECTOR_MATH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef AAF_CORE_KERNELS_VECTOR_MATH_INL_H_
#undef AAF_CORE_KERNELS_VECTOR_MATH_INL_H_
#else
#define AAF_CORE_KERNELS_VECTOR_MATH_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace aaf::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// fast_exp_nonpositive (fast_exp.h) with round-to-nearest by the 1.5 * 2^23
/// shift: exp(x) for x <= 0, relative error below 3e-7, a multiply then an
/// add at every step (never fused), so each lane gives the same bits on every target.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V exp_nonpositive(D d, V x) {
    const hn::RebindToSigned<D> di;
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

/// 2^x for x <= 0: x = k + f with k an integer and |f| <= 1/2, 2^k from the
/// exponent bits, 2^f a degree-4 polynomial (relative error 3e-6, fitted
/// with 2^0 = 1 exactly, so a zero exponent gives exactly 1). Floored at
/// 2^-64 (Max turns a NaN into that floor on x86): a weight that small
/// changes no sum it joins, and times a value it stays clear of the
/// denormals that slow arithmetic down. Cheaper than exp_nonpositive where
/// the caller folds log2(e) into its constants.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V exp2_nonpositive(D d, V x) {
    const hn::RebindToSigned<D> di;
    const V floored = hn::Max(x, hn::Set(d, -64.0f));
    const V rounding_shift = hn::Set(d, 12582912.0f);  // 1.5 * 2^23: the add rounds to an integer
    const V shifted = hn::Add(floored, rounding_shift);
    const V f = hn::Sub(floored, hn::Sub(shifted, rounding_shift));
    // Estrin's scheme, (1 + c1 f) + f^2 ((c2 + c3 f) + c4 f^2): a shorter
    // chain of dependent operations than Horner's, so more taps overlap.
    const V f2 = hn::Mul(f, f);
    const V low = hn::Add(hn::Mul(hn::Set(d, 0.693124175f), f), hn::Set(d, 1.0f));
    const V middle = hn::Add(hn::Mul(hn::Set(d, 0.0559064262f), f), hn::Set(d, 0.240240991f));
    const V high = hn::Add(middle, hn::Mul(hn::Set(d, 0.00958285294f), f2));
    const V p = hn::Add(low, hn::Mul(f2, high));
    // shifted's bits are 0x4B400000 + k: move k + 127 into the exponent field.
    const auto bits = hn::ShiftLeft<23>(hn::Add(hn::BitCast(di, shifted), hn::Set(di, 127 - 0x4B400000)));
    return hn::Mul(p, hn::BitCast(d, bits));
}

/// sin and cos of x: x = q pi/2 + r with q rounded to nearest (the 1.5 * 2^23
/// shift) and pi/2 split in three (Cody and Waite, Cephes' constants, q pi/2's
/// first part exact up to |q| = 2^16), Cephes' sinf/cosf polynomials on
/// |r| <= pi/4, then the quadrant's swap and signs. Absolute error about
/// 1e-7 for the phases here (|x| well under 1e4 radians); |x| is clamped to
/// 2^20 so that no input gives a non-finite value.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void sin_cos(D d, V x, V &sin_x, V &cos_x) {
    const hn::RebindToSigned<D> di;
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
    const auto swap = hn::RebindMask(d, hn::Ne(hn::And(quadrant, hn::Set(di, 1)), hn::Zero(di)));
    const auto negate_sin = hn::RebindMask(d, hn::Ne(hn::And(quadrant, hn::Set(di, 2)), hn::Zero(di)));
    const auto negate_cos =
        hn::RebindMask(d, hn::Ne(hn::And(hn::Add(quadrant, hn::Set(di, 1)), hn::Set(di, 2)), hn::Zero(di)));
    const V sin_r = hn::IfThenElse(swap, c, s), cos_r = hn::IfThenElse(swap, s, c);
    sin_x = hn::IfThenElse(negate_sin, hn::Neg(sin_r), sin_r);
    cos_x = hn::IfThenElse(negate_cos, hn::Neg(cos_r), cos_r);
}

}  // namespace HWY_NAMESPACE
}  // namespace aaf::detail
HWY_AFTER_NAMESPACE();

#endif
