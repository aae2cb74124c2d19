#include <limits>
#include <vector>

#include "aaf/core/analysis/spectral_filter.h"
#include "aaf/core/methods/maaf/maaf_components.h"

namespace aaf {

SpectralFilter maaf_spectral_filter(const DoubleWedge &wedge, int pairs, SpectralShape shape,
                                    bool mu_weights) {
    check_double_wedge(wedge);
    // The wedge alone (Sec. 5): no pixel band-limit clips it, Omega_x^max = inf.
    const std::vector<MaafComponent> parts = maaf_components(
        wedge.s_min, wedge.s_max, std::numeric_limits<double>::infinity(), wedge.omega_y_max, pairs);
    SpectralFilter filter{shape, {}};
    for (const MaafComponent &part : parts) {
        SpectralComponent c;
        c.weight = shape == SpectralShape::Gaussian && mu_weights ? part.weight
                                                                  : 1.0;  // MAAF Eq. 9-10; Table 1 unweighted
        c.center_x = part.centre_x;
        c.center_y = part.centre_y;
        c.width_x = part.sigma_x;
        c.width_y = part.sigma_y;
        filter.components.push_back(c);
    }
    return filter;
}

}  // namespace aaf
