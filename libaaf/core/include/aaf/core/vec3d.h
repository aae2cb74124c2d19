#pragma once

#include <cmath>

namespace aaf {

/// A double-precision 3-vector for the analytic light integrals, whose edge
/// terms lose digits in float for small or distant lights (NOTES-RATIO.md).
struct Vec3d {
    double x = 0, y = 0, z = 0;

    constexpr Vec3d() = default;
    constexpr Vec3d(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

    constexpr Vec3d operator+(Vec3d b) const { return {x + b.x, y + b.y, z + b.z}; }
    constexpr Vec3d operator-(Vec3d b) const { return {x - b.x, y - b.y, z - b.z}; }
    constexpr Vec3d operator-() const { return {-x, -y, -z}; }
    constexpr Vec3d operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3d operator/(double s) const { return {x / s, y / s, z / s}; }
};

constexpr double dot(Vec3d a, Vec3d b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3d cross(Vec3d a, Vec3d b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3d v) {
    return std::sqrt(dot(v, v));
}
inline Vec3d normalize(Vec3d v) {
    return v / length(v);
}

}  // namespace aaf
