#pragma once

#include <cmath>

namespace aaf {

/// A point of the unit disc.
struct DiscPoint {
    float x = 0, y = 0;
};

/// Shirley and Chiu's concentric map of the square [-1, 1]^2 onto the unit
/// disc: area-preserving and continuous, so stratified samples stay
/// stratified on the disc. ISG Sec. 4 passes its tap grid through it; the
/// tracer's thin lens takes its aperture points from it.
inline DiscPoint concentric_disc(float a, float b) {
    constexpr float kPi = 3.14159265358979323846f;
    if (a == 0 && b == 0) return {0, 0};
    float r, phi;
    if (std::fabs(a) > std::fabs(b)) {
        r = a;
        phi = (kPi / 4) * (b / a);
    } else {
        r = b;
        phi = (kPi / 2) - (kPi / 4) * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// concentric_disc() of the point (u1, u2) of the unit square [0, 1)^2.
inline DiscPoint concentric_disc_unit(float u1, float u2) {
    return concentric_disc(2 * u1 - 1, 2 * u2 - 1);
}

}  // namespace aaf
