#pragma once

#include <cmath>

namespace aaf {

/// A small 3-vector of T (float or double), after pbrt-v4's Vector3<T>: one
/// definition for the float vectors of the tracer and filters (Vec3) and
/// the double ones of the analytic light integrals (Vec3d, vec3d.h).
template <typename T>
struct Vector3 {
    using Scalar = T;
    T x = 0, y = 0, z = 0;

    constexpr Vector3() = default;
    constexpr Vector3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}

    constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vector3 operator+(Vector3 b) const { return {x + b.x, y + b.y, z + b.z}; }
    constexpr Vector3 operator-(Vector3 b) const { return {x - b.x, y - b.y, z - b.z}; }
    constexpr Vector3 operator-() const { return {-x, -y, -z}; }
    constexpr Vector3 operator*(T s) const { return {x * s, y * s, z * s}; }
    constexpr Vector3 operator/(T s) const { return {x / s, y / s, z / s}; }
    constexpr bool operator==(Vector3 b) const { return x == b.x && y == b.y && z == b.z; }
    constexpr bool operator!=(Vector3 b) const { return !(*this == b); }
};

/// Positions (world metres), directions, normals and colours, in float.
using Vec3 = Vector3<float>;

// The scalar's type is taken from the vector, so `2 * v` works for either.
template <typename T>
constexpr Vector3<T> operator*(typename Vector3<T>::Scalar s, Vector3<T> v) {
    return v * s;
}
template <typename T>
constexpr T dot(Vector3<T> a, Vector3<T> b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr Vector3<T> cross(Vector3<T> a, Vector3<T> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
inline T length(Vector3<T> v) {
    return std::sqrt(dot(v, v));
}
template <typename T>
inline Vector3<T> normalize(Vector3<T> v) {
    return v / length(v);
}
/// The componentwise product (a colour times a colour).
template <typename T>
constexpr Vector3<T> times(Vector3<T> a, Vector3<T> b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}

}  // namespace aaf
