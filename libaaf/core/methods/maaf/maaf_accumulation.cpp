#include "aaf/core/methods/maaf/maaf_accumulation.h"

#include <cmath>

#include "aaf/core/util/error.h"

namespace aaf {

std::string maaf_function_name(int function) {
    if (function == 0) return "c0";
    const int p = (function + 1) / 2;
    return (function % 2 == 1 ? "c" : "s") + std::to_string(p);
}

std::string maaf_channel_suffix(int pairs, int channel) {
    const int per_axis = maaf_functions_per_axis(pairs);
    return maaf_function_name(channel / per_axis) + maaf_function_name(channel % per_axis);
}

MaafLightSide::MaafLightSide(int pairs, double omega_y_max) {
    if (pairs < 1 || pairs > kMaafMaxPairs)
        throw Error("MAAF light side: between 1 and " + std::to_string(kMaafMaxPairs) + " pairs, got " +
                    std::to_string(pairs));
    if (!(omega_y_max >= 0) || !std::isfinite(omega_y_max))
        throw Error("MAAF light side: Omega_y^max must be finite and >= 0");
    pairs_ = pairs;
    for (int p = 1; p < pairs; ++p)
        centre_y_rad_per_m_[std::size_t(p)] = omega_y_max * 2.0 * p / (2.0 * pairs - 1.0);  // MAAF Eq. 6
}

void MaafLightSide::evaluate(double y_m, double *phi) const {
    phi[0] = 1.0;
    for (int p = 1; p < pairs_; ++p) {
        const double phase = centre_y_rad_per_m_[std::size_t(p)] * y_m;
        phi[2 * p - 1] = std::cos(phase);  // MAAF Eq. 20, h_c^p
        phi[2 * p] = std::sin(phase);      // MAAF Eq. 20, h_s^p
    }
}

void MaafLightSide::accumulate(double y1_m, double y2_m, double value, double unoccluded_value,
                               double *value_sums, double *unoccluded_sums) const {
    const int n = maaf_functions_per_axis(pairs_);
    double phi1[2 * kMaafMaxPairs], phi2[2 * kMaafMaxPairs];
    evaluate(y1_m, phi1);  // each light axis with its own coordinate
    evaluate(y2_m, phi2);
    for (int a = 0; a < n; ++a) {
        const double first = phi1[a];
        for (int b = 0; b < n; ++b) {
            const double light_side = first * phi2[b];  // product of the two subspaces (MAAF Fig. 7)
            value_sums[a * n + b] += value * light_side;
            unoccluded_sums[a * n + b] += unoccluded_value * light_side;
        }
    }
}

}  // namespace aaf
