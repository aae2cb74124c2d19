#include "aaf/core/ltc_ggx.h"

#include <algorithm>
#include <cmath>

#include "aaf/core/ltc_ggx_table.h"

namespace aaf::ltc_ggx {

namespace {

const float *cell(int row, int column) {
    return ltc_ggx_table::kData + 6 * (std::size_t(row) * std::size_t(ltc_ggx_table::kSize) + std::size_t(column));
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
    const double clamped_cosine_integral = polygon_form_factor(transformed);
    result.magnitude_term = clamped_cosine_integral * m.magnitude;
    result.fresnel_term = clamped_cosine_integral * m.fresnel;
    return result;
}

}  // namespace aaf::ltc_ggx
