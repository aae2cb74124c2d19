#pragma once

#include <vector>

namespace aaf {

/// One axis-aligned Gaussian of MAAF's Fourier-domain filter in one 2D (x, y)
/// subspace (Wu et al. 2017, MAAF Eq. 9): mu_p G(Omega_x - C_x^p; sigma_x^p)
/// G(Omega_y - C_y^p; sigma_y^p), with G(t; s) = exp(-t^2 / (2 s^2)) (peak 1).
///
/// Units: every frequency is in radians per metre (not cycles): the primal
/// form of the component is a Gaussian of standard deviation 1 / sigma
/// metres modulated by exp(j (C_x x + C_y y)) (MAAF Eq. 11), so a phase is
/// C_x * (displacement in metres). Read as boxes (Sec. 5), sigma_x and sigma_y
/// are the half-widths.
struct MaafComponent {
    int index = 0;        ///< p, from -(N-1) to N-1
    int sign = 0;         ///< sgn_p: 0 for p = 0, +1 or -1 otherwise (MAAF Eq. 7)
    double centre_x = 0;  ///< C_x^p, rad/m (MAAF Eq. 7)
    double centre_y = 0;  ///< C_y^p, rad/m (MAAF Eq. 6)
    double sigma_x = 0;   ///< sigma_x^p, rad/m (MAAF Eq. 8; sigma_x^0 for p = 0)
    double sigma_y = 0;   ///< sigma_y^p, rad/m (MAAF Eq. 8)
    double weight = 0;    ///< mu_p (MAAF Eq. 10); 1 for p = 0
};

/// The band a pixel's wedge is partitioned over, after MAAF Sec. 6.2's
/// clip: the wedge's extent along Omega_x, Omega_y^max / s_min, may not
/// exceed the pixel band-limit Omega_x^max, so Omega_y^max is lowered to
/// s_min Omega_x^max where it would. Returns that Omega_y^max (rad/m, >= 0;
/// 0 when s_min = 0). Arguments as maaf_components().
double maaf_partitioned_omega_y_max(double s_min, double s_max, double omega_x_max_rad_per_m,
                                    double omega_y_max_rad_per_m);

/// The 2N - 1 components covering the double wedge between slopes s_min and
/// s_max (MAAF Eq. 6-10), ordered p = -(N-1), ..., 0, ..., N-1; `pairs` = N.
///
/// s_min, s_max: the wedge's slopes (soft shadows: d1/d2 - 1, dimensionless),
/// 0 <= s_min <= s_max, s_max may be +inf. omega_x_max_rad_per_m: the pixel
/// band-limit along Omega_x (> 0, may be +inf when no clip is wanted);
/// omega_y_max_rad_per_m: the light's band-limit Omega_y^max (> 0, finite).
/// The partition uses maaf_partitioned_omega_y_max() (Sec. 6.2), so with
/// N = 1 the single component is AAF's filter (MAAF Eq. 2): sigma_x^0 =
/// min(Omega_y^max / s_min, Omega_x^max).
///
/// Degenerate wedges give finite numbers: s_min = s_max (a line) gives
/// components of width Omega_y^max / ((2N-1) s); s_min = 0 (contact) gives
/// Omega_y^max = 0 after the clip, all components at C_y = 0 with
/// sigma_y = 0 and the x extent of the pixel band-limit.
/// Throws aaf::Error for pairs < 1, negative or unordered or NaN slopes,
/// non-positive band-limits, or s_min = 0 with an infinite Omega_x^max (the
/// wedge would have no finite extent).
std::vector<MaafComponent> maaf_components(double s_min, double s_max, double omega_x_max_rad_per_m,
                                           double omega_y_max_rad_per_m, int pairs);

/// The components with p >= 0, ordered p = 0, ..., N-1: what the primal
/// filter needs, since each pair (p, -p) transforms to the real cos/sin form
/// of MAAF Eq. 12-13 (the p < 0 member is the mirror image of p).
std::vector<MaafComponent> maaf_pair_components(double s_min, double s_max, double omega_x_max_rad_per_m,
                                                double omega_y_max_rad_per_m, int pairs);

/// MAAF Eq. 9 evaluated at (omega_x, omega_y) (rad/m) for the given components.
double maaf_fourier_filter(const std::vector<MaafComponent> &components, double omega_x_rad_per_m,
                           double omega_y_rad_per_m);

}  // namespace aaf
