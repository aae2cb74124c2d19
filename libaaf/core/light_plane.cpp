#include "aaf/core/light_plane.h"

#include <cmath>

#include "aaf/core/error.h"

namespace aaf {

const char *to_string(LightProfile profile) {
    return profile == LightProfile::Gaussian ? "gaussian" : "uniform";
}

LightProfile light_profile_from_string(const std::string &name) {
    if (name == "gaussian") return LightProfile::Gaussian;
    if (name == "uniform") return LightProfile::Uniform;
    throw Error("unknown light profile '" + name + "' (expected gaussian or uniform)");
}

LightPlane LightPlane::square(Vec3 center, Vec3 normal, float side_m) {
    LightPlane light;
    light.center = center;
    light.normal = normalize(normal);
    // Any tangent frame works for a square; pick one that avoids the normal.
    Vec3 helper = std::fabs(light.normal.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    light.axis_v = normalize(cross(light.normal, helper));
    light.axis_u = cross(light.axis_v, light.normal);
    light.width_m = side_m;
    light.height_m = side_m;
    light.sigma_m = side_m / 2;  // effective width 2 sigma = side (AAF Eq. 15)
    return light;
}

void LightPlane::validate() const {
    constexpr float tolerance = 1e-3f;
    auto unit = [&](Vec3 v) { return std::fabs(length(v) - 1.0f) < tolerance; };
    if (!unit(normal) || !unit(axis_u) || !unit(axis_v))
        throw Error("light normal and axes must be unit vectors");
    if (std::fabs(dot(normal, axis_u)) > tolerance || std::fabs(dot(normal, axis_v)) > tolerance ||
        std::fabs(dot(axis_u, axis_v)) > tolerance)
        throw Error("light normal and axes must be orthogonal");
    if (!(width_m > 0) || !(height_m > 0) || !(sigma_m > 0))
        throw Error("light width, height and sigma must be positive");
}

}  // namespace aaf
