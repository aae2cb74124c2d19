#include "aaf/core/kernels/light_bandlimit.h"

#include <algorithm>
#include <cmath>

#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"

namespace aaf {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The 1D emission profile along one axis: exp(-x^2 / (2 sigma^2)) on
/// [-h, h] (sigma = 0: constant), normalised spectrum F(omega) = int p(x)
/// cos(omega x) dx / int p(x) dx, by the composite Simpson rule.
struct AxisProfile {
    double half_extent_m;
    double sigma_m;  ///< 0 for a uniform profile

    double density(double x) const { return sigma_m > 0 ? std::exp(-x * x / (2 * sigma_m * sigma_m)) : 1.0; }
    double spectrum(double omega) const {
        constexpr int kIntervals = 2048;  // even; cos(omega x) spans < 2 periods over [-h, h] here
        const double step = 2 * half_extent_m / kIntervals;
        double numerator = 0, denominator = 0;
        for (int i = 0; i <= kIntervals; ++i) {
            const double x = -half_extent_m + i * step;
            const double weight = (i == 0 || i == kIntervals) ? 1 : (i % 2 ? 4 : 2);
            numerator += weight * density(x) * std::cos(omega * x);
            denominator += weight * density(x);
        }
        return numerator / denominator;
    }
};

/// The frequency (1/m) at which the profile's spectrum first falls to
/// exp(-1/2), the value of a Gaussian's spectrum exp(-sigma^2 omega^2 / 2)
/// at omega = 1/sigma: so an untruncated Gaussian gives exactly 1/sigma.
double spectrum_bandlimit(const AxisProfile &axis) {
    const double target = std::exp(-0.5);
    // The spectrum decreases from 1 until its first zero, beyond pi / h for
    // a profile peaked at the centre; the crossing lies before it, and
    // before 3/sigma (where an untruncated Gaussian is at exp(-4.5)).
    double high = kPi / axis.half_extent_m;
    if (axis.sigma_m > 0) high = std::min(high, 3.0 / axis.sigma_m);
    double low = 0;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (low + high);
        (axis.spectrum(mid) > target ? low : high) = mid;
    }
    return 0.5 * (low + high);
}

/// Equivalent width: the spectrum's area over its peak, int F = 2 pi p(0) /
/// int p, equals sqrt(2 pi) / sigma for a Gaussian; matching it gives
/// sigma_b = int p / (sqrt(2 pi) p(0)), i.e. sigma erf(h / (sigma sqrt 2)),
/// or 2h / sqrt(2 pi) for a uniform profile.
double equivalent_width_bandlimit(const AxisProfile &axis) {
    const double sigma_b = axis.sigma_m > 0
                               ? axis.sigma_m * std::erf(axis.half_extent_m / (axis.sigma_m * std::sqrt(2.0)))
                               : 2 * axis.half_extent_m / std::sqrt(2 * kPi);
    return 1 / sigma_b;
}

}  // namespace

const char *to_string(LightBandlimit rule) {
    switch (rule) {
        case LightBandlimit::Sigma:
            return "sigma";
        case LightBandlimit::Spectrum:
            return "spectrum";
        default:
            return "equivalent_width";
    }
}

LightBandlimit light_bandlimit_from_string(const std::string &name) {
    if (name == "sigma") return LightBandlimit::Sigma;
    if (name == "spectrum") return LightBandlimit::Spectrum;
    if (name == "equivalent_width") return LightBandlimit::EquivalentWidth;
    throw Error("unknown light band-limit rule " + quoted(name) +
                " (expected sigma, spectrum or equivalent_width)");
}

LightBandlimitAxes light_bandlimit_axes_m(const LightPlane &light, LightBandlimit rule) {
    light.validate();
    if (rule == LightBandlimit::Sigma) return {light.sigma_m, light.sigma_m};
    const double sigma = light.profile == LightProfile::Gaussian ? double(light.sigma_m) : 0.0;
    auto axis_sigma = [&](double half_extent) {
        const AxisProfile axis{half_extent, sigma};
        // Beyond 8 sigma the truncation is invisible in float: the paper's Gaussian.
        const double axis_omega = sigma > 0 && half_extent >= 8 * sigma ? 1 / sigma
                                  : rule == LightBandlimit::Spectrum    ? spectrum_bandlimit(axis)
                                                                        : equivalent_width_bandlimit(axis);
        return float(1 / axis_omega);
    };
    return {axis_sigma(0.5 * light.width_m), axis_sigma(0.5 * light.height_m)};
}

float light_bandlimit_sigma_m(const LightPlane &light, LightBandlimit rule) {
    const LightBandlimitAxes axes = light_bandlimit_axes_m(light, rule);
    return std::min(axes.u_m, axes.v_m);
}

}  // namespace aaf
