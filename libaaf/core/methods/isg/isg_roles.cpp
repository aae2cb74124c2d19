#include "aaf/core/methods/isg/isg_roles.h"

namespace aaf {

std::vector<RoleInfo> isg_shadow_roles() {
    return {
        {roles::HardVisibility,
         {"isg.V"},
         "0 or 1",
         "ISG Sec. 3.1's image-space hard shadow: 1 where one shadow ray from the primary hit to the key "
         "light's centre reaches it, 0 where it is blocked (in shadow); 1 on the background"},
        {roles::OccluderDistance,
         {"isg.occluder_m"},
         "metres, 0 = not in shadow",
         "distance from the primary hit to the first occluder on that ray (d of ISG Eq. 8)"},
    };
}

std::vector<RoleInfo> isg_glossy_roles() {
    return {
        {roles::Reflection,
         {"reflect.R", "reflect.G", "reflect.B"},
         "linear radiance",
         "ISG Sec. 3.2's reflection map: radiance along the mirror reflection of the primary ray (every "
         "light "
         "towards its centre, hard shadows), 0 where it leaves the scene",
         true},
        {roles::ReflectionDistance,
         {"reflect.E"},
         "metres, 0 = nothing reflected",
         "distance from the primary hit to the reflected object (E of ISG Eq. 13)"},
        {roles::ThetaMax,
         {"gloss.theta_max"},
         "radians, 0 = not glossy",
         "the material's glossy cone half-angle theta_max (ISG Fig. 4): its glossy BRDF is zero outside it"},
        {roles::GlossyReference,
         {"glossy.R", "glossy.G", "glossy.B"},
         "linear radiance",
         "distribution-ray-traced glossy reflection: the mean over the pixel's spp rays, uniform in solid "
         "angle within theta_max of the mirror direction, of the radiance the reflection map records (rays "
         "below the surface count 0); equals the reflection map where theta_max = 0",
         true},
        {roles::GlossyReflection,
         {"isg_glossy.R", "isg_glossy.G", "isg_glossy.B"},
         "linear radiance",
         "output of `aaf filter isg-glossy`: the reflection map gathered over the glossy cone (ISG Eq. "
         "10-14)",
         true},
    };
}

std::vector<RoleInfo> isg_dof_roles() {
    return {
        {roles::PinholeBeauty,
         {"pinhole.R", "pinhole.G", "pinhole.B"},
         "linear radiance",
         "the in-focus image a pinhole camera sees, r(x) V(x) of the key light; with a thin lens the "
         "beauty is the defocused reference of this",
         true},
        {roles::Defocused,
         {"isg_dof.R", "isg_dof.G", "isg_dof.B"},
         "linear radiance",
         "output of `aaf filter isg-dof`: the pinhole image gathered over circles of confusion (ISG Eq. "
         "15-17)",
         true},
    };
}

}  // namespace aaf
