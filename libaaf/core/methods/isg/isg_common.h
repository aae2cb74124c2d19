#pragma once

// What the three ISG methods share beyond the formulas of aaf/core/methods/isg/isg_formulas.h:
// their common parameters, header attributes and the scene size of ISG Sec. 5
// (their per-pixel loops: isg_rows.h).
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "aaf/core/framework/method.h"
#include "aaf/core/math/vec3.h"
#include "aaf/core/methods/isg/isg_formulas.h"
#include "aaf/core/methods/isg/isg_roles.h"

namespace aaf::isg {

/// The settings every ISG method shares, read from its parameters.
struct CommonSettings {
    int search_samples = 25;
    int gather_samples = 25;
    TapPattern pattern = TapPattern::Grid;
    float sigma = 1e-3f;       ///< range constant, relative to the scene size squared (ISG Sec. 5)
    float scene_size_m = 0;    ///< 0 = the diagonal of the positions' bounding box
    float max_radius_px = 64;  ///< every search and gather radius is clamped to this
};

/// Declarations for a method whose settings derive from CommonSettings,
/// starting with the parameters every ISG method declares, in this order:
/// search_samples, gather_samples, pattern, sigma, scene_size, max_radius.
template <class Settings>
ParameterDeclarations<Settings> common_parameters(std::string method) {
    using C = CommonSettings;
    const std::vector<std::pair<std::string, int>> counts = {{"1", 1},   {"9", 9},   {"25", 25},
                                                             {"49", 49}, {"81", 81}, {"121", 121}};
    return std::move(
        ParameterDeclarations<Settings>(std::move(method))
            .choice("search_samples", &C::search_samples, counts,
                    "Taps of the parameter search, a k x k pattern (ISG Table 1's 9/25/49/81)")
            .choice("gather_samples", &C::gather_samples, counts,
                    "Taps of the gather, a k x k pattern (ISG Table 1's 9/25/49/81)")
            .choice("pattern", &C::pattern,
                    {{"grid", TapPattern::Grid}, {"stratified", TapPattern::Stratified}},
                    "grid: the regular grid ISG Sec. 4 maps to the disc; stratified: one fixed jittered tap "
                    "per cell")
            .real(
                "sigma", &C::sigma, "",
                "Range constant sigma of the Gaussian on world distance, in units of the scene size squared "
                "(ISG Sec. 5: near 1e-3 scaled by the inverse scene size)",
                0, 1e6, /*min_open=*/true)
            .real("scene_size", &C::scene_size_m, "metres",
                  "Scene size the range constants scale with; 0 = the positions' bounding-box diagonal", 0,
                  1e9)
            .real("max_radius", &C::max_radius_px, "pixels", "Largest search or gather radius", 0, 4096));
}

/// A float or Vec3 header attribute; throws aaf::InputError naming a missing
/// or mistyped one (and a Vec3 with a NaN or infinite component).
float float_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name);
Vec3 vec3_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name);
/// float_attribute() in (0, max_value]; NaN and infinity are refused, naming the attribute.
float positive_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name,
                         float max_value);
/// float_attribute(), finite and >= 0 (an aperture radius: 0 = a pinhole).
float non_negative_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name);
/// attr::kCameraFocalPx of an image `height` pixels tall: positive, and at
/// most 1e6 x height (a field of view of at least 1e-6 rad), past which the
/// screen projections of ISG Sec. 3 overflow.
float focal_px_attribute(const std::map<std::string, AttributeValue> &attributes, int height);

/// The three channels of a role as one vector-valued view.
struct Vec3Planes {
    ConstPlaneView c[3];
    Vec3 operator()(int x, int y) const { return {c[0](x, y), c[1](x, y), c[2](x, y)}; }
};
Vec3Planes vec3_input(const MethodImages &images, Role role);

/// Inline: scene_size_m() calls it for every pixel.
inline bool all_finite(Vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The scene size ISG Sec. 5 scales its range constants by: `scene_size_m`
/// when positive, else the diagonal of the bounding box of the finite
/// positions (1 when there are none or they coincide).
float scene_size_m(const Vec3Planes &position, int width, int height, float scene_size_m);

}  // namespace aaf::isg
