#include "aaf/core/contract/light_plane.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"

namespace aaf {

const char *to_string(LightProfile profile) {
    return profile == LightProfile::Gaussian ? "gaussian" : "uniform";
}

LightProfile light_profile_from_string(const std::string &name) {
    if (name == "gaussian") return LightProfile::Gaussian;
    if (name == "uniform") return LightProfile::Uniform;
    throw Error("unknown light profile " + quoted(name) + " (expected gaussian or uniform)");
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

namespace {

std::string describe(float value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

std::string describe(Vec3 v) {
    return describe(v.x) + " " + describe(v.y) + " " + describe(v.z);
}

bool is_finite(Vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

void LightPlane::validate(const LightFieldNames &names) const {
    // Unit and orthogonal to float accuracy after a round trip through a
    // header (and normalisation in single precision).
    constexpr float tolerance = 1e-3f;
    if (!is_finite(center)) throw InputError(names.center + " must be finite (is " + describe(center) + ")");
    const std::pair<Vec3, const std::string *> directions[] = {
        {normal, &names.normal}, {axis_u, &names.axis_u}, {axis_v, &names.axis_v}};
    for (const auto &direction : directions)
        if (!is_finite(direction.first) || !(std::fabs(length(direction.first) - 1.0f) < tolerance))
            throw InputError(*direction.second + " must be a unit vector (is " + describe(direction.first) +
                             ")");
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b)
            if (!(std::fabs(dot(directions[a].first, directions[b].first)) < tolerance))
                throw InputError(*directions[a].second + " and " + *directions[b].second +
                                 " must be orthogonal");
    const std::pair<float, const std::string *> sizes[] = {
        {width_m, &names.width}, {height_m, &names.height}, {sigma_m, &names.sigma}};
    for (const auto &size : sizes)
        if (!(size.first > 0) || !std::isfinite(size.first))
            throw InputError(*size.second + " must be positive and finite (is " + describe(size.first) + ")");
}

namespace {

/// The profile's variance along one axis of half-extent `half_extent_m` (light_plane.h).
float axis_variance_m2(const LightPlane &light, float half_extent_m) {
    const double h = half_extent_m;
    if (light.profile == LightProfile::Uniform) return float(h * h / 3);
    const double sigma = light.sigma_m, t = h / sigma;
    const double phi = std::exp(-0.5 * t * t) / std::sqrt(2 * 3.14159265358979323846);
    return float(sigma * sigma * (1 - 2 * t * phi / std::erf(t / std::sqrt(2.0))));
}

}  // namespace

float LightPlane::variance_u_m2() const {
    return axis_variance_m2(*this, 0.5f * width_m);
}

float LightPlane::variance_v_m2() const {
    return axis_variance_m2(*this, 0.5f * height_m);
}

}  // namespace aaf
