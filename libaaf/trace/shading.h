#pragma once

#include <algorithm>
#include <cmath>

#include "scene_description.h"

namespace aaf::trace {

/// BRDF of `material` at a point with unit normal `n`, for unit directions to
/// the viewer `wo` and to the light `wi`: Lambert plus, when the material has
/// one, a GGX (Trowbridge-Reitz) lobe with Smith's separable masking and
/// Schlick's Fresnel. Units 1/sr, per channel.
inline Vec3 evaluate_brdf(const Material &material, Vec3 n, Vec3 wo, Vec3 wi) {
    constexpr float kInvPi = 0.318309886f;
    Vec3 f = material.albedo * kInvPi;
    const float cos_o = dot(n, wo), cos_i = dot(n, wi);
    if (!material.has_specular() || cos_o <= 0 || cos_i <= 0) return f;
    const Vec3 h = normalize(wo + wi);
    const float alpha = material.roughness * material.roughness;
    const float alpha_sq = alpha * alpha;
    const float cos_h = std::max(0.0f, dot(n, h));
    const float denom = cos_h * cos_h * (alpha_sq - 1.0f) + 1.0f;
    const float distribution = alpha_sq * kInvPi / (denom * denom);
    auto masking = [&](float c) { return 2.0f * c / (c + std::sqrt(alpha_sq + (1.0f - alpha_sq) * c * c)); };
    const float geometry = masking(cos_i) * masking(cos_o);
    const float schlick = std::pow(1.0f - std::max(0.0f, dot(wi, h)), 5.0f);
    const float common = distribution * geometry / (4.0f * cos_i * cos_o);
    for (int c = 0; c < 3; ++c) {
        const float fresnel = material.specular[c] + (1.0f - material.specular[c]) * schlick;
        (c == 0 ? f.x : c == 1 ? f.y : f.z) += fresnel * common;
    }
    return f;
}

}  // namespace aaf::trace
