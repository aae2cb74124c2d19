#pragma once

#include <algorithm>
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

}  // namespace aaf
