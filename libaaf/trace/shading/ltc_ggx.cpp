#include "aaf/trace/shading/ltc_ggx.h"

#include <algorithm>
#include <cmath>

#include "aaf/trace/shading/ggx.h"
#include "ltc_ggx_table.h"

namespace aaf::ltc_ggx {

namespace {

const float *cell(int row, int column) {
    return ltc_ggx_table::kData +
           6 * (std::size_t(row) * std::size_t(ltc_ggx_table::kSize) + std::size_t(column));
}

/// The solid-angle-weighted mean direction of a polygon above the horizon,
/// unnormalised: the vector form factor sum_k theta_k (v_k x v_k+1) / |v_k x v_k+1|,
/// oriented to the upper hemisphere.
Vec3d mean_direction(const LocalPolygon &polygon) {
    Vec3d sum{0, 0, 0};
    for (int k = 0; k < polygon.count; ++k) {
        const Vec3d a = polygon.vertices[std::size_t(k)],
                    b = polygon.vertices[std::size_t((k + 1) % polygon.count)];
        const Vec3d c = cross(a, b);
        const double sine = length(c);
        if (sine > 0) sum = sum + c * (std::atan2(sine, dot(a, b)) / sine);
    }
    return sum.z < 0 ? sum * -1.0 : sum;
}

}  // namespace

Coefficients lookup(double roughness, double cos_view) {
    const int n = ltc_ggx_table::kSize;
    const double u = std::clamp(roughness, 0.0, 1.0) * (n - 1);
    const double v = std::sqrt(std::clamp(1 - cos_view, 0.0, 1.0)) * (n - 1);
    const int i = std::min(int(u), n - 2), j = std::min(int(v), n - 2);
    const double fu = u - i, fv = v - j;
    double value[6];
    for (int k = 0; k < 6; ++k)
        value[k] = (1 - fu) * ((1 - fv) * cell(i, j)[k] + fv * cell(i, j + 1)[k]) +
                   fu * ((1 - fv) * cell(i + 1, j)[k] + fv * cell(i + 1, j + 1)[k]);
    return {value[0], value[1], value[2], value[3], value[4], value[5]};
}

PolygonIntegral integrate(const LocalPolygon &polygon, double roughness, double cos_view) {
    PolygonIntegral result;
    if (!(cos_view > 0)) return result;
    const Coefficients m = lookup(roughness, cos_view);
    // LTC Eq. 10: the integral of D over P is that of the clamped cosine D_o
    // over M^-1 P; the edge formula needs the transformed polygon clipped to
    // the upper hemisphere.
    LocalPolygon transformed;
    for (int k = 0; k < polygon.count; ++k) {
        const Vec3d p = polygon.vertices[std::size_t(k)];
        transformed.add({m.a * p.x + m.b * p.z, m.c * p.y, m.d * p.x + p.z});
    }
    const LocalPolygon clipped = clip_to_upper_hemisphere(transformed);
    if (clipped.count < 3) return result;
    const double clamped_cosine_integral = std::fabs(polygon_edge_integral(clipped));
    result.magnitude_term = clamped_cosine_integral * m.magnitude;
    // Schlick's weight at the polygon's mean direction under the LTC (the
    // mean over M^-1 P mapped back by M), not the table's hemispherical mean:
    // a light sees only its part of the lobe, and near grazing views the
    // hemispherical mean is dominated by directions the light does not cover.
    const Vec3d f = mean_direction(clipped);
    const double det =
        m.a - m.b * m.d;  // M = [[1 / det, 0, -b / det], [0, 1 / c, 0], [-d / det, 0, a / det]]
    const Vec3d wi = normalize(Vec3d{(f.x - m.b * f.z) / det, f.y / m.c, (m.a * f.z - m.d * f.x) / det});
    const Vec3d wo{std::sqrt(std::max(0.0, 1 - cos_view * cos_view)), 0, cos_view};
    if (wi.z > 0) result.fresnel_term = result.magnitude_term * ggx::schlick_weight(wo, wi);
    return result;
}

}  // namespace aaf::ltc_ggx
