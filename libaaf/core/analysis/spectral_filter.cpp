#include "aaf/core/analysis/spectral_filter.h"

#include <cmath>
#include <string>

#include "aaf/core/util/error.h"

namespace aaf {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

double spectral_profile(SpectralShape shape, double u) {
    if (shape == SpectralShape::Box) return std::abs(u) <= 1.0 ? 1.0 : 0.0;
    return std::exp(-0.5 * u * u);
}

double SpectralFilter::value(double omega_x, double omega_y) const {
    double sum = 0;
    for (const SpectralComponent &c : components) {
        const double dy = omega_y - c.center_y;
        const double dx = omega_x - c.center_x - c.shear * dy;
        sum += c.weight * spectral_profile(shape, dx / c.width_x) * spectral_profile(shape, dy / c.width_y);
    }
    return sum;
}

double SpectralFilter::integral() const {
    // A box of half-widths (a, b) has area 4ab; exp(-u^2/(2 s^2)) integrates to sqrt(2 pi) s per axis.
    const double per_unit = shape == SpectralShape::Box ? 4.0 : 2.0 * kPi;
    double sum = 0;
    for (const SpectralComponent &c : components) sum += c.weight * per_unit * c.width_x * c.width_y;
    return sum;
}

SpectralFilter aaf_spectral_filter(const DoubleWedge &wedge, SpectralShape shape) {
    check_double_wedge(wedge);
    SpectralComponent c;
    c.width_x = wedge.omega_y_max / wedge.s_min;  // MAAF Eq. 2: G(Omega_x; Omega_y^max / s_min)
    c.width_y = wedge.omega_y_max;                // MAAF Eq. 2: G(Omega_y; Omega_y^max)
    return {shape, {c}};
}

SpectralFilter fsf_spectral_filter(const DoubleWedge &wedge, SpectralShape shape) {
    check_double_wedge(wedge);
    const double spread = wedge.omega_y_max * (1.0 / wedge.s_min - 1.0 / wedge.s_max);
    SpectralComponent c;
    c.shear = 0.5 * (1.0 / wedge.s_min + 1.0 / wedge.s_max);  // 1/s_avg, s_avg the harmonic mean (MAAF Eq. 4)
    // The wedge spans Omega_y (1/s_max - 1/s_avg) .. Omega_y (1/s_min - 1/s_avg) about the shear
    // line, at most spread/2 either side at |Omega_y| = Omega_y^max: the tight parallelogram's
    // half-width. MAAF Eq. 4's Gaussian has sigma = spread.
    c.width_x = shape == SpectralShape::Box ? 0.5 * spread : spread;
    c.width_y = wedge.omega_y_max;  // MAAF Eq. 4: G(Omega_y; Omega_y^max)
    return {shape, {c}};
}

}  // namespace aaf
