#pragma once

#include <cmath>

namespace aaf::trace {

/// Shirley-Chiu concentric map of the unit square onto the unit disc: the
/// thin lens's aperture point for (u1, u2) in [0, 1)^2, area-preserving and
/// continuous, so stratified samples stay stratified on the disc.
inline void concentric_disc(float u1, float u2, float &dx, float &dy) {
    constexpr float kPi = 3.14159265358979323846f;
    const float a = 2 * u1 - 1, b = 2 * u2 - 1;
    if (a == 0 && b == 0) {
        dx = dy = 0;
        return;
    }
    float r, phi;
    if (std::fabs(a) > std::fabs(b)) {
        r = a;
        phi = (kPi / 4) * (b / a);
    } else {
        r = b;
        phi = (kPi / 2) - (kPi / 4) * (a / b);
    }
    dx = r * std::cos(phi);
    dy = r * std::sin(phi);
}

}  // namespace aaf::trace
