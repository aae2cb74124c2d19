#pragma once

#include <array>
#include <vector>

#include "aaf/core/contract/light_plane.h"
#include "aaf/core/contract/plane_view.h"

namespace aaf {

/// How MAAF turns a first pass's occluder distances into per-pixel wedges.
struct MaafWedgeParams {
    /// Omega_y^max times the light's sigma, dimensionless: the light's band-limit
    /// Omega_y^max = light_band / sigma_m in rad/m. The paper's 2 (MAAF Sec. 3,
    /// Omega_y^max = 2 / sigma_y). The pixel band-limit uses the same scale,
    /// Omega_x^max = light_band / ((1 + s_min) d) (AAF Eq. 6 with alpha = 1), so
    /// with N = 1 the filter is AAF's with k mu = light_band (AAF Eq. 8, 13).
    double light_band = 2.0;
    /// Unoccluded pixels borrow occluder distances from occluded pixels of the
    /// same object within this radius (AAF Sec. 6); pixels.
    int fill_radius_px = 5;
    /// Slopes are averaged over a (2r + 1)^2 window (MAAF Sec. 6.2: 5x5); pixels.
    int prefilter_radius_px = 2;
    /// Neighbours whose normal turns more than this are left out of the average; degrees.
    float normal_threshold_deg = 20.0f;

    /// Throws aaf::Error naming the first parameter out of range.
    void validate() const;
};

/// The light's band-limit Omega_y^max = light_band / sigma, rad/m.
double maaf_light_omega_y_max(const LightPlane &light, double light_band);

/// Per-pixel inputs, all of one size (aov_contract.h for meanings and units);
/// d2_min/d2_max hold 0 where no occluder was hit.
struct MaafWedgeInputs {
    ConstPlaneView d1;
    ConstPlaneView d2_min;
    ConstPlaneView d2_max;
    std::array<ConstPlaneView, 3> normal;
    ConstPlaneView object_id;
    ConstPlaneView pixel_size;
};

/// Per-pixel wedges, row-major. A pixel without one (background, no occluder
/// within the fill radius) has s_min = s_max = 0, omega_x_max = 0 (the filter
/// leaves it as it is) and omega_y = the light's Omega_y^max (its sums still
/// serve as taps of its neighbours).
struct MaafWedges {
    int width = 0, height = 0;
    std::vector<float> s_min, s_max;  ///< slopes d1/d2 - 1 (MAAF Sec. 3), prefiltered
    std::vector<float> omega_x_max;   ///< pixel band-limit, rad/m; 0 = no wedge
    std::vector<float> omega_y;       ///< partitioned Omega_y^max (maaf_components.h), rad/m
};

/// MAAF Sec. 6.2's parameter estimate: slopes from the occluder distances
/// (with AAF Sec. 6's fill for unoccluded pixels), averaged over the window
/// among pixels of the same object whose normals agree, then the pixel and
/// partitioned band-limits. Runs on the current oneTBB arena; the result
/// does not depend on the thread count. Throws aaf::Error on mismatched
/// sizes or bad parameters.
MaafWedges maaf_pixel_wedges(const MaafWedgeInputs &inputs, const LightPlane &light,
                             const MaafWedgeParams &params);

}  // namespace aaf
