#pragma once

#include "aaf/trace/shading/polygon_irradiance.h"

namespace aaf {

/// The GGX lobe of ggx.h (separable Smith masking) integrated over a polygon
/// with linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt 2016): the
/// lobe f(wo, wi) cos(theta_i) is approximated by magnitude * D, D a clamped
/// cosine transformed by a 3x3 matrix M, whose integral over a polygon is the
/// clamped cosine's over the polygon transformed by M^-1 (LTC Eq. 9-10).
/// M^-1 is fitted per (roughness, view angle) by scripts/ltc_fit (its
/// README section gives the fit's error against brute-force integration).
namespace ltc_ggx {

/// Roughness (sqrt of GGX alpha) below which the table holds the fit at this
/// value: sharper lobes are evaluated as this one (the fit's clamp).
inline constexpr double kMinRoughness = 0.05;
/// Cosine of the view angle at which the table's grazing column is fitted;
/// views closer to grazing use it.
inline constexpr double kMinCosView = 1e-3;

/// One table entry, bilinearly interpolated: M^-1 = [[a, 0, b], [0, c, 0],
/// [d, 0, 1]] in the ShadingFrame (view in the x-z plane), the lobe's
/// hemispherical integral `magnitude` (no Fresnel) and `fresnel`, the same
/// integral weighted by Schlick's (1 - wi . h)^5 (the fit's record; integrate()
/// weights each polygon by Schlick at its own mean direction instead).
struct Coefficients {
    double a = 1, b = 0, c = 1, d = 0;
    double magnitude = 0;
    double fresnel = 0;
};

/// The interpolated coefficients for `roughness` in [0, 1] and the cosine of
/// the view angle `cos_view` in (0, 1] (table axes: roughness and
/// sqrt(1 - cos_view), both uniform).
Coefficients lookup(double roughness, double cos_view);

/// The two integrals over a polygon whose Schlick-weighted combination
/// F0 * magnitude_term + (1 - F0) * fresnel_term approximates the polygon's
/// integral of f(wo, wi) cos(theta_i) (uniform radiance 1): the LTC's
/// clamped-cosine integral over M^-1 P times `magnitude`, and that times
/// Schlick's weight (1 - wi . h)^5 at the polygon's mean direction under the
/// LTC (not the table's `fresnel`, the lobe's hemispherical mean, which near
/// grazing views is dominated by directions a light does not cover).
struct PolygonIntegral {
    double magnitude_term = 0;
    double fresnel_term = 0;
};

/// The GGX lobe of `roughness` integrated over `polygon` (vertices in the
/// ShadingFrame of the normal and the view, whose cosine to the normal is
/// `cos_view`); zero when the view is at or below the horizon.
PolygonIntegral integrate(const LocalPolygon &polygon, double roughness, double cos_view);

}  // namespace ltc_ggx
}  // namespace aaf
