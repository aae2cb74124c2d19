#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace aaf {

/// exp(x) for x <= 0 in float, branch-free so filter loops vectorise: range
/// reduction x = k ln2 + r with |r| <= ln2/2 and a degree-6 Taylor polynomial
/// for exp(r); relative error below 3e-7 (about std::exp's float accuracy).
/// Inputs below -87 (and -inf) are clamped there (result ~1.6e-38, still a
/// normal float); positive inputs are clamped to 0; NaN counts as below -87,
/// so no input gives NaN, and the exponent never leaves [-126, 0].
inline float fast_exp_nonpositive(float x) {
    constexpr float kLog2e = 1.44269504088896341f;
    constexpr float kLn2Hi = 0.693145751953125f;  // ln 2 split so k * kLn2Hi is exact
    constexpr float kLn2Lo = 1.428606765330187045e-06f;
    // Written as comparisons so that NaN (false in both) lands on -87 rather
    // than reaching the int conversion below (undefined for NaN).
    const float above_floor = x > -87.0f ? x : -87.0f;
    const float clamped = above_floor < 0.0f ? above_floor : 0.0f;
    const float k =
        static_cast<float>(static_cast<int>(clamped * kLog2e - 0.5f));  // round to nearest (x <= 0)
    const float r = (clamped - k * kLn2Hi) - k * kLn2Lo;
    float p = 1.0f / 720.0f;
    p = p * r + 1.0f / 120.0f;
    p = p * r + 1.0f / 24.0f;
    p = p * r + 1.0f / 6.0f;
    p = p * r + 0.5f;
    p = p * r + 1.0f;
    p = p * r + 1.0f;
    // Scale by 2^k through the exponent bits.
    const std::uint32_t bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(k) + 127) << 23;
    float scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return p * scale;
}

/// exp(x) for x <= 0 as the gather kernels compute it (gather_rows.cpp),
/// written out as their reference. The same clamps as fast_exp_nonpositive;
/// k = round(x log2 e) by adding 1.5 * 2^23 (whose float has unit spacing,
/// so the sum rounds to the nearest integer and its low bits hold k); the
/// split ln 2 of Cody and Waite; a degree-5 polynomial for exp(r), |r| <=
/// ln2/2, interpolated at Chebyshev nodes with p(0) = 1 and p'(0) = 1
/// exactly (five multiply-adds where the Taylor form needs six). With
/// `Fused` each multiply-add is rounded once (std::fma), as the kernels do
/// on instruction sets with fused multiply-add (x86 AVX2 and AVX-512, Arm);
/// without it a multiply then an add, as they do on the others (SSE4).
/// Relative error below 3e-7 either way (test_fast_exp.cpp).
template <bool Fused>
inline float gather_exp_nonpositive(float x) {
    const auto mul_add = [](float a, float b, float c) { return Fused ? std::fma(a, b, c) : a * b + c; };
    constexpr float kLog2e = 1.44269504088896341f;
    constexpr float kRoundingShift = 12582912.0f;  // 1.5 * 2^23
    constexpr float kLn2Hi = 0.693145751953125f;   // k * kLn2Hi is exact
    constexpr float kLn2Lo = 1.428606765330187045e-06f;
    const float above_floor = x > -87.0f ? x : -87.0f;  // NaN lands on -87
    const float clamped = above_floor < 0.0f ? above_floor : 0.0f;
    const float shifted = mul_add(clamped, kLog2e, kRoundingShift);
    const float k = shifted - kRoundingShift;  // exact: an integer in [-126, 0]
    const float r = mul_add(-k, kLn2Lo, mul_add(-k, kLn2Hi, clamped));
    float p = 0.00836377405f;
    p = mul_add(p, r, 0.0418798551f);
    p = mul_add(p, r, 0.166665733f);
    p = mul_add(p, r, 0.499993473f);
    p = mul_add(p, r, 1.0f);
    p = mul_add(p, r, 1.0f);
    // 2^k through the exponent bits: shifted's bits are those of 1.5 * 2^23 plus k.
    std::int32_t shifted_bits;
    std::memcpy(&shifted_bits, &shifted, sizeof shifted_bits);
    const std::uint32_t bits = static_cast<std::uint32_t>(shifted_bits - (0x4B400000 - 127)) << 23;
    float scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return p * scale;
}

}  // namespace aaf
