#pragma once

// Brute-force integrals over a rectangular light's surface, the independent
// reference for the analytic U (polygon_irradiance.h, ltc_ggx.h): tensor
// Gauss-Legendre on a grid of cells, the grid doubled until two successive
// results agree. Shared by tests/core and scripts/ltc_fit/ltc_error.cpp
// (which documents the LTC fit's error with these placements).

#include <cmath>
#include <vector>

#include "aaf/trace/shading/ggx.h"
#include "aaf/trace/shading/polygon_irradiance.h"

namespace aaf::ltc_reference {

/// A rectangle corner + s ex + t ey, s, t in [0, 1], emitting towards
/// `normal`, all relative to the shading point, in its frame (z = normal,
/// view in the x-z plane).
struct Rectangle {
    Vec3d corner, ex, ey;
    Vec3d normal() const { return normalize(cross(ex, ey)); }
    LocalPolygon polygon() const {
        LocalPolygon p;
        p.add(corner);
        p.add(corner + ex);
        p.add(corner + ex + ey);
        p.add(corner + ey);
        return p;
    }
};

/// Integral over the rectangle's area of integrand(w) * cos_light / r^2,
/// w the unit direction to the area element (0 where the element's back
/// faces the point); refined until the relative change is below `tolerance`
/// or the grid reaches `max_cells` per side.
template <typename Integrand>
double integrate_over_area(const Rectangle &light, const Integrand &integrand, double tolerance = 1e-7,
                           int max_cells = 1024) {
    static const double node[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                   0.8611363115940526};
    static const double weight[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                     0.3478548451374538};
    const Vec3d n = light.normal();
    const double area = length(cross(light.ex, light.ey));
    double previous = -1;
    for (int cells = 8;; cells *= 2) {
        double sum = 0;
        for (int j = 0; j < cells; ++j)
            for (int i = 0; i < cells; ++i)
                for (int b = 0; b < 4; ++b)
                    for (int a = 0; a < 4; ++a) {
                        const double s = (i + 0.5 + 0.5 * node[a]) / cells,
                                     t = (j + 0.5 + 0.5 * node[b]) / cells;
                        const Vec3d y = light.corner + light.ex * s + light.ey * t;
                        const double r_sq = dot(y, y);
                        const Vec3d w = y / std::sqrt(r_sq);
                        const double cos_light = -dot(n, w);
                        if (!(cos_light > 0)) continue;
                        sum += weight[a] * weight[b] * 0.25 * integrand(w) * cos_light / r_sq;
                    }
        sum *= area / (double(cells) * cells);
        if (std::fabs(sum - previous) <= tolerance * std::fabs(sum) || cells >= max_cells) return sum;
        previous = sum;
    }
}

/// The form factor by quadrature: cos(theta) / pi above the horizon.
inline double form_factor_by_quadrature(const Rectangle &light) {
    constexpr double kPi = 3.14159265358979323846;
    return integrate_over_area(light, [](Vec3d w) { return w.z > 0 ? w.z / kPi : 0.0; });
}

/// The GGX lobe f cos (no Fresnel, or Schlick's weight when `fresnel`) by quadrature.
inline double ggx_by_quadrature(const Rectangle &light, Vec3d wo, double roughness, bool fresnel,
                                double tolerance = 1e-5, int max_cells = 1024) {
    const double alpha = roughness * roughness;
    return integrate_over_area(
        light,
        [&](Vec3d w) {
            const double value = ggx::cosine_weighted(wo, w, alpha);
            return fresnel && value > 0 ? value * ggx::schlick_weight(wo, w) : value;
        },
        tolerance, max_cells);
}

/// A square light of side `side` centred at unit direction `direction` *
/// `distance`, facing the point (its normal along -direction).
inline Rectangle facing_square(Vec3d direction, double distance, double side) {
    const Vec3d d = normalize(direction);
    const Vec3d helper = std::fabs(d.z) < 0.9 ? Vec3d{0, 0, 1} : Vec3d{1, 0, 0};
    const Vec3d u = normalize(cross(helper, d)), v = cross(d, u);
    // Wound so that cross(ex, ey) points back at the shading point.
    return {d * distance - u * (side / 2) - v * (side / 2), v * side, u * side};
}

/// The light placements of the GGX sweep for a view at `view_deg` from the
/// normal: around the mirror direction, beside it, overhead, and one partly
/// below the horizon.
inline std::vector<Rectangle> ggx_placements(double view_deg) {
    constexpr double kPi = 3.14159265358979323846;
    const double theta = view_deg * kPi / 180;
    const Vec3d mirror{-std::sin(theta), 0, std::cos(theta)};
    return {facing_square(mirror, 2.0, 1.0), facing_square(Vec3d{0.2, 0.8, 1.0}, 2.0, 1.5),
            facing_square(Vec3d{0, 0, 1}, 3.0, 2.0), facing_square(Vec3d{-1.0, 0.3, 0.15}, 2.0, 1.5)};
}

}  // namespace aaf::ltc_reference
