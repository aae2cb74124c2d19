#pragma once

#include <cmath>
#include <string>

#include "aaf/core/math/vec3.h"

namespace aaf {

/// Emission profile of a planar area light over its rectangle.
enum class LightProfile {
    Gaussian,  ///< intensity exp(-r^2 / (2 sigma^2)), truncated at the rectangle's edges
    Uniform,   ///< constant intensity over the rectangle
};

const char *to_string(LightProfile profile);
/// Parses "gaussian" or "uniform"; throws aaf::Error otherwise.
LightProfile light_profile_from_string(const std::string &name);

/// How LightPlane::validate() names each field in its messages (a header
/// reader names its attributes instead).
struct LightFieldNames {
    std::string center = "light center", normal = "light normal", axis_u = "light axis_u",
                axis_v = "light axis_v", width = "light width", height = "light height",
                sigma = "light sigma";
};

/// A planar rectangular area light: the geometry of AAF Fig. 2(a).
///
/// Convention (one place for the whole toolkit): for a square light of side L
/// the default is sigma = L / 2, so the light's "effective width" 2 sigma of
/// AAF Eq. 15 equals its side, A_l = (2 sigma)^2 = L^2, and the Gaussian is
/// truncated at 1 sigma from the centre. The filter and the sampling rate use
/// `sigma_m` for both profiles; the tracer uses it to shape a Gaussian light.
struct LightPlane {
    Vec3 center;            ///< world metres
    Vec3 normal{0, -1, 0};  ///< unit, the side the light emits towards
    Vec3 axis_u{1, 0, 0};   ///< unit tangent along the rectangle's width
    Vec3 axis_v{0, 0, 1};   ///< unit tangent along the rectangle's height
    float width_m = 1.0f;   ///< extent along axis_u
    float height_m = 1.0f;  ///< extent along axis_v
    float sigma_m = 0.5f;   ///< standard deviation of the emission profile, metres
    LightProfile profile = LightProfile::Gaussian;

    /// A square light of side `side_m` centred at `center`, facing `normal`,
    /// with the default sigma = side / 2.
    static LightPlane square(Vec3 center, Vec3 normal, float side_m);

    /// Throws aaf::InputError "<field> <problem>" (a light comes from a scene
    /// or an image header) unless the centre is finite, the normal and axes
    /// are finite orthonormal vectors and width, height and sigma are positive
    /// and finite.
    void validate(const LightFieldNames &names = LightFieldNames{}) const;

    /// Distance of `p` from the light's plane, measured along its normal:
    /// the d1 (receiver) and d2 (occluder) of AAF Fig. 2 and Eq. 2, in metres.
    float plane_distance_m(Vec3 p) const { return std::fabs(dot(normal, p - center)); }

    /// Squared distance between two world points measured in a plane parallel
    /// to the light (motion along the light's normal excluded), AAF Eq. 12.
    float in_plane_distance_sq(Vec3 a, Vec3 b) const {
        Vec3 delta = a - b;
        float along_normal = dot(normal, delta);
        return dot(delta, delta) - along_normal * along_normal;
    }

    /// Variance (metres^2) of the emission profile's coordinate along axis_u
    /// (half-extent width/2) or axis_v (height/2): sigma^2 (1 - 2 t phi(t) /
    /// erf(t / sqrt 2)) at t = h / sigma for the truncated Gaussian, h^2 / 3
    /// for the uniform profile.
    float variance_u_m2() const;
    float variance_v_m2() const;
    /// World point at offsets (u_m, v_m) from the centre along the tangent axes.
    Vec3 point_at(float u_m, float v_m) const { return center + axis_u * u_m + axis_v * v_m; }
};

}  // namespace aaf
