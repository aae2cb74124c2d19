#pragma once

#include <vector>

#include "aaf/core/contract/aov_contract.h"

/// The roles and header attributes of Image Space Gathering (Robison and
/// Shirley 2009): the tracer's isg group writes them, `aaf filter
/// isg-shadow`, `isg-glossy` and `isg-dof` read them (methods/isg/isg_roles.cpp).
namespace aaf {

namespace roles {
inline constexpr Role HardVisibility{
    "hard_visibility"};  ///< one shadow ray to the key light's centre, 1 = reached it
inline constexpr Role OccluderDistance{
    "occluder_distance"};                        ///< distance from the hit to that ray's occluder
inline constexpr Role Reflection{"reflection"};  ///< radiance along the mirror reflection
inline constexpr Role ReflectionDistance{
    "reflection_distance"};                                 ///< distance from the hit to the reflected object
inline constexpr Role ThetaMax{"theta_max"};                ///< the material's glossy cone half-angle
inline constexpr Role GlossyReference{"glossy_reference"};  ///< the glossy reflection by cone sampling
inline constexpr Role PinholeBeauty{"pinhole"};             ///< the in-focus image a pinhole camera sees
inline constexpr Role GlossyReflection{
    "glossy_reflection"};                      ///< output of isg-glossy: the filtered reflection
inline constexpr Role Defocused{"defocused"};  ///< output of isg-dof: the defocused image
}  // namespace roles

/// Written by the tracer's isg group (ISG's screen projections need them).
namespace attr {
inline constexpr const char *kCameraEye = "aaf:camera:eye";           // Vec3, world metres
inline constexpr const char *kCameraFocalPx = "aaf:camera:focal_px";  // float, height / (2 tan(fov_y / 2))
inline constexpr const char *kFocusDistance = "aaf:camera:focus_distance_m";  // float, plane in focus
}  // namespace attr

/// Each ISG method's own roles: channels, units and meanings.
std::vector<RoleInfo> isg_shadow_roles();
std::vector<RoleInfo> isg_glossy_roles();
std::vector<RoleInfo> isg_dof_roles();

}  // namespace aaf
