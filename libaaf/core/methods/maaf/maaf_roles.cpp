#include "aaf/core/methods/maaf/maaf_roles.h"

#include "aaf/core/methods/maaf/maaf_accumulation.h"

namespace aaf {

std::vector<std::string> maaf_contract_channels(const std::string &prefix, bool rgb) {
    std::vector<std::string> names;
    for (int c = 0; c < maaf_channel_count(kMaafContractPairs); ++c) {
        const std::string base = prefix + maaf_channel_suffix(kMaafContractPairs, c);
        if (!rgb) {
            names.push_back(base);
            continue;
        }
        for (const char *colour : {".R", ".G", ".B"}) names.push_back(base + colour);
    }
    return names;
}

std::vector<RoleInfo> maaf_roles() {
    return {
        {roles::MaafValueSums, maaf_contract_channels("maaf.V_", false), "light weight, summed over samples",
         "MAAF Eq. 20/23 by Monte Carlo, N = 3: channel V_<a><b> is the sum over the pixel's samples of l(y) "
         "f(x, y) phi_a(y1) phi_b(y2), with y1, y2 the sample's point on the light along its axis_u and "
         "axis_v "
         "(metres from its centre) and phi_c0 = 1, phi_cp = cos(C_y^p y), phi_sp = sin(C_y^p y), C_y^p = "
         "maaf.omegay 2p / 5 rad/m (MAAF Eq. 6); `aaf::MaafLightSide::accumulate` writes it for any "
         "renderer"},
        {roles::MaafUnoccludedSums, maaf_contract_channels("maaf.W_", false),
         "light weight, summed over samples",
         "as maaf.V_* with every sample counted unoccluded (f = 1): the filter divides by these, filtered "
         "alike, so a fully lit region stays exactly lit"},
        {roles::MaafWedge,
         {"maaf.smin", "maaf.smax", "maaf.omegax", "maaf.omegay"},
         "slopes (unitless); rad/m",
         "the wedge the MAAF sums were accumulated with (MAAF Sec. 6.2: from the first pass, averaged over "
         "5x5): "
         "slopes d1/d2 - 1, the pixel band-limit Omega_x^max (0 = no wedge, not filtered) and the "
         "partitioned "
         "Omega_y^max of the light-side functions"},
        {roles::MaafWindowWedge,
         {"maaf.window.smin", "maaf.window.smax"},
         "slopes (unitless)",
         "maaf_wedge's slopes over a temporal window (`--temporal-window` writes them in memory, never to a "
         "file): the smallest s_min and the largest s_max; the filter takes its widths from them where the "
         "partitioned Omega_y^max, and so the sums' phases, stay the same"},
    };
}

}  // namespace aaf
