#pragma once

#include "aaf/core/contract/light_plane.h"
#include "aaf/core/math/vec3.h"

namespace aaf {

/// A surface's reflectance as the ratio estimator's analytic U sees it: a
/// Lambertian lobe plus an optional GGX lobe (aaf/trace/shading/ggx.h) with Schlick's
/// Fresnel, the tracer's BRDF (libaaf/trace/shading.h).
struct SurfaceReflectance {
    Vec3 albedo;             ///< diffuse reflectance per channel, [0, 1]
    Vec3 specular;           ///< Fresnel reflectance at normal incidence F0 per channel; 0 = no GGX lobe
    float roughness = 0.5f;  ///< GGX alpha = roughness^2, (0, 1]
};

/// A one-sided rectangular light of uniform radiance: its rectangle
/// (LightPlane's centre, axes, width and height; the profile is not used)
/// and its radiance per channel, W / (m^2 sr).
struct RectLight {
    LightPlane plane;
    Vec3 radiance;
};

/// The unshadowed direct light U (ratio estimator Eq. 20) reflected towards
/// the viewer, split by lobe: per channel, W / (m^2 sr).
struct UnshadowedLight {
    Vec3 diffuse;   ///< albedo * radiance * form factor: exact (horizon-clipped edge integral)
    Vec3 specular;  ///< GGX lobe by linearly transformed cosines (ltc_ggx.h; within its fit error)
    Vec3 total() const { return diffuse + specular; }
};

/// U at the point `p` with unit shading normal `n` seen from the unit
/// direction `wo`: the integral over the light's solid angle of
/// f(wo, wi) L max(0, n . wi). Zero when `p` lies behind the light's emitting
/// side or the rectangle lies below the horizon of `n`; no specular term when
/// `wo` lies at or below that horizon (the BRDF has none there).
UnshadowedLight rect_light_unshadowed(const RectLight &light, Vec3 p, Vec3 n, Vec3 wo,
                                      const SurfaceReflectance &surface);

}  // namespace aaf
