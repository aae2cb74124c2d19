#include "aaf/core/analysis/wedge_spectrum.h"

#include <cmath>
#include <random>
#include <string>

#include "aaf/core/util/error.h"

namespace aaf {

void check_double_wedge(const DoubleWedge &wedge) {
    if (!(std::isfinite(wedge.s_min) && std::isfinite(wedge.s_max) && wedge.s_min > 0 &&
          wedge.s_max > wedge.s_min))
        throw Error("double wedge needs 0 < s_min < s_max, got s_min " + std::to_string(wedge.s_min) +
                    ", s_max " + std::to_string(wedge.s_max));
    if (!(std::isfinite(wedge.omega_y_max) && wedge.omega_y_max > 0))
        throw Error("double wedge needs Omega_y^max > 0, got " + std::to_string(wedge.omega_y_max));
}

bool in_double_wedge(const DoubleWedge &wedge, double omega_x, double omega_y) {
    if (std::abs(omega_y) > wedge.omega_y_max) return false;
    // Between the lines Omega_x = Omega_y/s_max and Omega_y/s_min, on either side of the origin.
    const double near = omega_y / wedge.s_max, far = omega_y / wedge.s_min;
    return omega_y >= 0 ? (omega_x >= near && omega_x <= far) : (omega_x <= near && omega_x >= far);
}

double double_wedge_area(const DoubleWedge &wedge) {
    // MAAF Sec. 5: two triangles of height Omega_y^max and base Omega_y^max (1/s_min - 1/s_max).
    return wedge.omega_y_max * wedge.omega_y_max * (1.0 / wedge.s_min - 1.0 / wedge.s_max);
}

std::vector<DoubleWedge> uniform_sorted_wedges(int count, std::uint64_t seed, double s_upper,
                                               double omega_y_max) {
    if (count < 0) throw Error("wedge count must be >= 0, got " + std::to_string(count));
    if (!(std::isfinite(s_upper) && s_upper > 0))
        throw Error("upper slope must be > 0, got " + std::to_string(s_upper));
    std::mt19937_64 engine(seed);
    // The top 53 bits as a double in [0, 1): the same on every standard library.
    const auto uniform = [&] { return double(engine() >> 11) * 0x1.0p-53 * s_upper; };
    std::vector<DoubleWedge> wedges;
    wedges.reserve(std::size_t(count));
    while (int(wedges.size()) < count) {
        const double a = uniform(), b = uniform();
        if (a == 0 || b == 0 || a == b) continue;
        wedges.push_back({std::min(a, b), std::max(a, b), omega_y_max});
    }
    return wedges;
}

}  // namespace aaf
