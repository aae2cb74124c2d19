#include "spherical_rectangle.h"

#include <algorithm>
#include <cmath>

namespace aaf::trace {

namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3d to_double(Vec3 v) {
    return {double(v.x), double(v.y), double(v.z)};
}

}  // namespace

SphericalRectangle::SphericalRectangle(const LightPlane &light, Vec3d p) : p_(p) {
    width_ = light.width_m;
    height_ = light.height_m;
    x_ = to_double(light.axis_u);
    y_ = to_double(light.axis_v);
    normal_ = to_double(light.normal);
    ex_ = x_ * width_;
    ey_ = y_ * height_;
    corner_ = to_double(light.center) - ex_ * 0.5 - ey_ * 0.5;
    const double plane_offset = dot(normal_, p - corner_);  // > 0 on the emitting side
    visible_ = plane_offset > 0;
    if (!visible_) return;
    // Urena et al. Sec. 3: the local frame of the rectangle with the point at
    // the origin and the rectangle in the plane z = z0 < 0.
    z_ = cross(x_, y_);
    const Vec3d d = corner_ - p;
    x0_ = dot(d, x_);
    y0_ = dot(d, y_);
    z0_ = dot(d, z_);
    if (z0_ > 0) {
        z0_ = -z0_;
        z_ = -z_;
    }
    x1_ = x0_ + width_;
    y1_ = y0_ + height_;
    const Vec3d v00{x0_, y0_, z0_}, v01{x0_, y1_, z0_}, v10{x1_, y0_, z0_}, v11{x1_, y1_, z0_};
    const Vec3d n0 = normalize(cross(v00, v10)), n1 = normalize(cross(v10, v11));
    const Vec3d n2 = normalize(cross(v11, v01)), n3 = normalize(cross(v01, v00));
    // Interior angles of the spherical rectangle; its solid angle is their sum minus 2 pi.
    const double g0 = std::acos(std::clamp(-dot(n0, n1), -1.0, 1.0));
    const double g1 = std::acos(std::clamp(-dot(n1, n2), -1.0, 1.0));
    const double g2 = std::acos(std::clamp(-dot(n2, n3), -1.0, 1.0));
    const double g3 = std::acos(std::clamp(-dot(n3, n0), -1.0, 1.0));
    b0_ = n0.z;
    b1_ = n2.z;
    k_ = 2 * kPi - g2 - g3;
    solid_angle_sr_ = g0 + g1 - k_;
    solid_angle_mode_ =
        solid_angle_sr_ >= kMinSolidAngle_sr && -z0_ >= kMinPlaneDistance * std::max(width_, height_);
}

Vec3d SphericalRectangle::sample(double u1, double u2) const {
    if (!solid_angle_mode_) return corner_ + ex_ * u1 + ey_ * u2;
    // Urena et al. Sec. 4 (Algorithm 1): the x coordinate from the solid
    // angle up to it, then y uniform in the height's projection h.
    const double au = u1 * solid_angle_sr_ + k_;
    const double fu = (std::cos(au) * b0_ - b1_) / std::sin(au);
    double cu = 1 / std::sqrt(fu * fu + b0_ * b0_) * (fu > 0 ? 1 : -1);
    cu = std::clamp(cu, -1.0, 1.0);
    double xu = -(cu * z0_) / std::sqrt(std::max(1e-300, 1 - cu * cu));
    xu = std::clamp(xu, x0_, x1_);
    const double d = std::sqrt(xu * xu + z0_ * z0_);
    const double h0 = y0_ / std::sqrt(d * d + y0_ * y0_);
    const double h1 = y1_ / std::sqrt(d * d + y1_ * y1_);
    const double hv = h0 + u2 * (h1 - h0), hv_sq = hv * hv;
    const double yv = hv_sq < 1 - 1e-12 ? hv * d / std::sqrt(1 - hv_sq) : y1_;
    const double yv_clamped = std::clamp(yv, y0_, y1_);
    return p_ + x_ * xu + y_ * yv_clamped + z_ * z0_;
}

double SphericalRectangle::pdf(Vec3d y) const {
    if (solid_angle_mode_) return 1 / solid_angle_sr_;
    const Vec3d to_light = y - p_;
    const double distance_sq = dot(to_light, to_light);
    const double cos_light = -dot(normal_, to_light) / std::sqrt(distance_sq);
    if (!(cos_light > 0)) return 0;
    // Area density 1 / A converted to solid angle: r^2 / (A cos_light).
    return distance_sq / (width_ * height_ * cos_light);
}

bool SphericalRectangle::intersect(Vec3d direction, Vec3d &y) const {
    const double facing = -dot(normal_, direction);
    if (!visible_ || !(facing > 0)) return false;
    const double t = dot(normal_, p_ - corner_) / facing;
    y = p_ + direction * t;
    const Vec3d local = y - corner_;
    const double u = dot(local, x_), v = dot(local, y_);
    return u >= 0 && u <= width_ && v >= 0 && v <= height_;
}

}  // namespace aaf::trace
