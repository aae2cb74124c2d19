#pragma once

#include "aaf/core/math/vec3d.h"

namespace aaf {

/// The GGX (Trowbridge-Reitz) specular lobe the tracer shades with
/// (libaaf/trace/shading.h), in double and in a local frame whose z axis is
/// the surface normal: distribution D, Smith's separable masking G1(i) G1(o),
/// no Fresnel. alpha = roughness^2, in (0, 1].
namespace ggx {

/// D(h) for cos(theta_h) = `cos_h`, 1/sr.
double distribution(double cos_h, double alpha);
/// Smith's G1 of one direction with cosine `cos_theta` to the normal.
double masking(double cos_theta, double alpha);
/// f(wo, wi) cos(theta_i) without Fresnel for unit `wo`, `wi`: D G1 G1 / (4 cos_o);
/// 0 when either lies below the horizon. 1/sr.
double cosine_weighted(Vec3d wo, Vec3d wi, double alpha);
/// Schlick's weight (1 - wi . h)^5 of the half vector of unit `wo`, `wi`, so that
/// F = F0 + (1 - F0) * weight.
double schlick_weight(Vec3d wo, Vec3d wi);
/// A direction wi by reflecting `wo` about a half vector drawn from D(h) cos(theta_h)
/// with uniforms u1, u2 in [0, 1); may lie below the horizon.
Vec3d sample(Vec3d wo, double alpha, double u1, double u2);
/// The solid-angle density of sample() producing `wi`: D(h) cos(theta_h) / (4 |wo . h|).
double sample_pdf(Vec3d wo, Vec3d wi, double alpha);

}  // namespace ggx
}  // namespace aaf
