#include "aaf/core/methods/ratio/ratio_roles.h"

namespace aaf {

std::vector<RoleInfo> ratio_roles() {
    return {
        {roles::RatioAnalytic,
         {"ratio.U.R", "ratio.U.G", "ratio.U.B"},
         "linear radiance",
         "ratio estimator Eq. 20: the analytic unshadowed direct light U of every light, summed (exact "
         "polygon irradiance for the diffuse lobe, linearly transformed cosines for GGX). Per light: the "
         "same names with `ratio.` replaced by `ratio.L<i>.`, i < aaf:ratio:lights",
         true,
         true},  // colour, per light
        {roles::RatioShadowed,
         {"ratio.S.R", "ratio.S.G", "ratio.S.B"},
         "linear radiance",
         "ratio estimator Eq. 21 as a mean: (1/N) sum of w R L V / p over the pixel's N samples per light "
         "(MIS weights w), summed over lights; it is also the full-stochastic estimate (ratio estimator Eq. "
         "10). Per light as ratio_u",
         true,
         true},  // colour, per light
        {roles::RatioUnshadowed,
         {"ratio.Un.R", "ratio.Un.G", "ratio.Un.B"},
         "linear radiance",
         "ratio estimator Eq. 22 as a mean: the same samples and weights as ratio_s with V = 1, so S_N / U_N "
         "stays in [0, 1]; U - U_N + S_N is the control-variate estimate (ratio estimator Eq. 11). Per light "
         "as ratio_u",
         true,
         true},  // colour, per light
        {roles::RatioShadowedLuminance,
         {"ratio.S.Y"},
         "luminance",
         "Rec. 709 luminance of ratio_s, for the grey approximation (ratio estimator Sec. 3.4). Per light as "
         "ratio_u",
         false,
         true},  // data, per light
        {roles::RatioUnshadowedLuminance,
         {"ratio.Un.Y"},
         "luminance",
         "Rec. 709 luminance of ratio_un (ratio estimator Sec. 3.4). Per light as ratio_u",
         false,
         true},  // data, per light
        {roles::RatioDirect,
         {"ratio.direct.R", "ratio.direct.G", "ratio.direct.B"},
         "linear radiance",
         "output of `aaf filter ratio`: the direct light it estimates, U den(S_N) / den(U_N) summed over the "
         "lights (ratio estimator Eq. 9); R,G,B are the beauty with ratio_s replaced by it",
         true},
    };
}

}  // namespace aaf
