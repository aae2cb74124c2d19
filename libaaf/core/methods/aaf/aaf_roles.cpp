#include "aaf/core/methods/aaf/aaf_roles.h"

namespace aaf {

std::vector<RoleInfo> aaf_roles() {
    return {
        {roles::FilterWidth,
         {"aaf_beta.X"},
         "metres, 0 = not filtered",
         "output of `aaf filter aaf`: Gaussian standard deviation beta of AAF Eq. 13 (a layer of its own "
         "with one "
         "single-letter channel, so Blender's compositor shows it as a pass; aaf 0.1 named it `aaf.beta`, "
         "still "
         "read)"},
        {roles::PlannedSpp,
         {"plan.spp"},
         "samples",
         "output of `aaf plan`: total light samples per pixel from AAF Eq. 21"},
    };
}

}  // namespace aaf
