#include "aaf/core/methods/maaf6/maaf6_roles.h"

#include "aaf/core/methods/maaf/maaf_roles.h"

namespace aaf {

std::vector<RoleInfo> maaf6_roles() {
    return {
        {roles::Maaf6Direct,
         {"maaf6.direct.R", "maaf6.direct.G", "maaf6.direct.B"},
         "linear radiance",
         "MAAF 6D (Sec. 6.2): mean over the pixel's path samples of the direct light at the lens ray's hit, "
         "one shadow ray to the area light; the beauty of a maaf6 render is this plus maaf6_indirect"},
        {roles::Maaf6Indirect,
         {"maaf6.indirect.R", "maaf6.indirect.G", "maaf6.indirect.B"},
         "linear radiance",
         "MAAF 6D: mean of the one-bounce diffuse indirect light (cosine-sampled bounce, one shadow ray at "
         "the "
         "bounce point), 0 when the effect is off"},
        {roles::Maaf6DirectSums, maaf_contract_channels("maaf6.direct.V_", true),
         "linear radiance, summed over samples",
         "MAAF Eq. 23 by Monte Carlo, N = 3: V_<a><b>.R/G/B is the sum over the pixel's samples of the "
         "direct "
         "radiance times phi_a(y1, u1) phi_b(y2, u2); phi_c0 = 1, phi_cp = cos(C_y^p y + C_u^p u), phi_sp = "
         "sin(...), y_i the light point and u_i the lens point along the pixel's tangent axis t_i (metres), "
         "C from `aaf::maaf6_pair_components` of maaf6_wedge; `aaf::Maaf6SampleSide::accumulate` writes it"},
        {roles::Maaf6DirectWeights, maaf_contract_channels("maaf6.direct.W_", false),
         "luminance, summed over samples",
         "as maaf6_direct_sums with the sample's unoccluded luminance (its radiance with visibility 1) "
         "instead of "
         "its radiance: the filter divides by these, filtered alike, and multiplies by the pixel's own mean"},
        {roles::Maaf6IndirectSums, maaf_contract_channels("maaf6.indirect.V_", true),
         "linear radiance, summed over samples",
         "as maaf6_direct_sums for the indirect radiance, with y_i = the bounce direction's tan along t_i "
         "(unitless, the unit plane above the receiver)"},
        {roles::Maaf6IndirectWeights, maaf_contract_channels("maaf6.indirect.W_", false), "samples",
         "as maaf6_direct_sums for the indirect layer with weight 1 (channel c0c0 counts the samples)"},
        {roles::Maaf6Wedge,
         {"maaf6.direct.ymin", "maaf6.direct.ymax", "maaf6.indirect.ymin", "maaf6.indirect.ymax",
          "maaf6.umin", "maaf6.umax", "maaf6.omegax"},
         "slopes: unitless (direct, u), metres (indirect); rad/m",
         "the 3D wedges of the first pass averaged over 5x5 (MAAF Sec. 6.2): direct y slopes d1/d2 - 1, "
         "indirect y slopes = reflector distance z, defocus slopes 1 - z/F (either sign), -1 in both y "
         "channels = no y-wedge; the pixel band-limit 2 / pixel size"},
        {roles::Maaf6WindowWedge,
         {"maaf6.window.direct.ymin", "maaf6.window.direct.ymax", "maaf6.window.indirect.ymin",
          "maaf6.window.indirect.ymax", "maaf6.window.umin", "maaf6.window.umax"},
         "as maaf6_wedge",
         "maaf6_wedge's slopes over a temporal window (`--temporal-window` writes them in memory, never to "
         "a file): the y-wedges' smallest y_min and largest y_max (-1 where no frame has a y-wedge), the "
         "u-wedge's smallest u_min and largest u_max; the filter takes the widths the sums' phases leave "
         "free from them (the axis-aligned filter's, and the pairs' where the phases are the same)"},
        {roles::Maaf6Spp,
         {"maaf6.spp"},
         "samples",
         "path samples of the pixel: --spp plus the focal-plane extra (MAAF Sec. 6.2, at most 100)"},
    };
}

}  // namespace aaf
