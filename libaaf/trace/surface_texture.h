#pragma once

#include <cmath>

#include "scene_description.h"

namespace aaf::trace {

/// A material as one surface point sees it: the albedo after its texture and
/// the shading normal after its normal perturbation. Every shading path (the
/// beauty, r(x), the ratio estimator's U, S_N and U_N) shades with this, so
/// textures and normal maps affect them alike. Untextured materials come
/// back unchanged, bit for bit.
struct TexturedSurface {
    Material material;  ///< albedo replaced by the texture's value at the point
    Vec3 normal;        ///< unit shading normal, on the geometric normal's side
};

/// The textured material of `material` at world point `p` with unit geometric
/// normal `n` (facing the viewer).
inline TexturedSurface texture_surface(const Material &material, Vec3 p, Vec3 n) {
    TexturedSurface surface{material, n};
    if (material.checker_size_m > 0) {
        // Cell parity of the 3D checker; the small offset keeps axis-aligned
        // faces at a cell boundary (common in scenes) off the boundary.
        const float inverse = 1 / material.checker_size_m;
        const long parity = long(std::floor(p.x * inverse + 1e-3f)) +
                            long(std::floor(p.y * inverse + 1e-3f)) + long(std::floor(p.z * inverse + 1e-3f));
        if (parity & 1) surface.material.albedo = material.checker_albedo;
    }
    if (material.bump_slope > 0) {
        const float k = 6.28318531f / material.bump_period_m;
        const Vec3 gradient =
            Vec3{std::cos(k * p.x), std::cos(k * p.y), std::cos(k * p.z)} * material.bump_slope;
        const Vec3 tangential = gradient - n * dot(n, gradient);
        surface.normal = normalize(n - tangential);
    }
    return surface;
}

}  // namespace aaf::trace
