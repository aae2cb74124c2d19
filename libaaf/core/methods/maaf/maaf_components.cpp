#include "aaf/core/methods/maaf/maaf_components.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "aaf/core/util/error.h"

namespace aaf {

namespace {

/// G(t; s) of MAAF Eq. 9-10 with peak 1; s = 0 is the limit (1 at t = 0, else 0).
double peak_one_gaussian(double t, double s) {
    if (!(s > 0)) return t == 0 ? 1.0 : 0.0;
    return std::exp(-t * t / (2.0 * s * s));
}

void check_arguments(double s_min, double s_max, double omega_x_max, double omega_y_max, int pairs) {
    if (pairs < 1) throw Error("MAAF needs at least one filter pair (N >= 1), got " + std::to_string(pairs));
    if (!(s_min >= 0) || !(s_max >= s_min))
        throw Error("MAAF wedge slopes must satisfy 0 <= s_min <= s_max (got " + std::to_string(s_min) +
                    ", " + std::to_string(s_max) + ")");
    if (!(omega_x_max > 0)) throw Error("MAAF pixel band-limit Omega_x^max must be positive");
    if (!(omega_y_max > 0) || !std::isfinite(omega_y_max))
        throw Error("MAAF light band-limit Omega_y^max must be positive and finite");
    if (s_min == 0 && std::isinf(omega_x_max))
        throw Error("MAAF wedge with s_min = 0 needs a finite pixel band-limit Omega_x^max");
}

}  // namespace

double maaf_partitioned_omega_y_max(double s_min, double s_max, double omega_x_max, double omega_y_max) {
    check_arguments(s_min, s_max, omega_x_max, omega_y_max, 1);
    // MAAF Sec. 6.2: the Omega_x extent Omega_y^max / s_min is bounded by Omega_x^max.
    return std::min(omega_y_max, s_min * omega_x_max);
}

namespace {

/// Components p of [first, pairs - 1] of the wedge (MAAF Eq. 6-10), after check_arguments().
std::vector<MaafComponent> components_from(double s_min, double s_max, double omega_x_max, double omega_y_max,
                                           int pairs, int first) {
    const double omega = maaf_partitioned_omega_y_max(s_min, s_max, omega_x_max, omega_y_max);
    // The wedge's Omega_x extents at Omega_y = omega along its two edges,
    // written so that s_min = 0 and s_max = inf stay finite.
    const double extent_at_s_min = s_min > 0 ? std::min(omega_y_max / s_min, omega_x_max) : omega_x_max;
    const double extent_at_s_max = omega > 0 ? omega / s_max : 0.0;
    const double segments = 2.0 * pairs - 1.0;  // 2N - 1 equal slices of [-omega, omega]

    std::vector<MaafComponent> components;
    components.reserve(std::size_t(pairs - first));
    for (int p = first; p <= pairs - 1; ++p) {
        MaafComponent c;
        c.index = p;
        c.sign = (p > 0) - (p < 0);
        const double inner = (2.0 * std::abs(p) - 1.0) / segments;  // (2|p| - 1) / (2N - 1)
        const double outer = (2.0 * std::abs(p) + 1.0) / segments;  // (2|p| + 1) / (2N - 1)
        c.centre_y = omega * 2.0 * p / segments;                    // MAAF Eq. 6
        c.centre_x = 0.5 * c.sign * (extent_at_s_max * inner + extent_at_s_min * outer);  // MAAF Eq. 7
        c.sigma_y = omega / segments;                                                     // MAAF Eq. 8
        c.sigma_x = p == 0 ? extent_at_s_min / segments  // MAAF Eq. 8, the p = 0 case stated after it
                           : 0.5 * (extent_at_s_min * outer - extent_at_s_max * inner);  // MAAF Eq. 8
        // MAAF Eq. 10: a Gaussian over the whole wedge.
        c.weight = peak_one_gaussian(c.centre_x, extent_at_s_min) * peak_one_gaussian(c.centre_y, omega);
        components.push_back(c);
    }
    return components;
}

}  // namespace

std::vector<MaafComponent> maaf_components(double s_min, double s_max, double omega_x_max, double omega_y_max,
                                           int pairs) {
    check_arguments(s_min, s_max, omega_x_max, omega_y_max, pairs);
    return components_from(s_min, s_max, omega_x_max, omega_y_max, pairs, -(pairs - 1));
}

std::vector<MaafComponent> maaf_pair_components(double s_min, double s_max, double omega_x_max,
                                                double omega_y_max, int pairs) {
    check_arguments(s_min, s_max, omega_x_max, omega_y_max, pairs);
    return components_from(s_min, s_max, omega_x_max, omega_y_max, pairs, 0);  // p >= 0 only
}

double maaf_fourier_filter(const std::vector<MaafComponent> &components, double omega_x, double omega_y) {
    double sum = 0;
    for (const MaafComponent &c : components)  // MAAF Eq. 9
        sum += c.weight * peak_one_gaussian(omega_x - c.centre_x, c.sigma_x) *
               peak_one_gaussian(omega_y - c.centre_y, c.sigma_y);
    return sum;
}

}  // namespace aaf
