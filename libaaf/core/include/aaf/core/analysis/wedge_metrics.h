#pragma once

#include "aaf/core/analysis/spectral_filter.h"
#include "aaf/core/analysis/wedge_spectrum.h"

namespace aaf {

/// The grids of integrate_filter_metrics. Both are n x n midpoint rules:
/// - over T, in coordinates fitted to the wedge: Omega_y = Omega_y^max v with
///   v in [-1, 1], Omega_x = Omega_y (1/s_max + t (1/s_min - 1/s_max)) with
///   t in [0, 1], Jacobian (Omega_y^max)^2 |v| (1/s_min - 1/s_max), so the
///   wedge's edges are cell edges and its area is exact;
/// - over the filter's bounding rectangle [-X, X] x [-Y, Y], X and Y the
///   largest |Omega_x|, |Omega_y| any component reaches (boxes: their edges;
///   Gaussians: tail_sigmas standard deviations, beyond which they count as 0).
/// Box edges inside the rectangle make the error O(1/n).
struct WedgeIntegrationGrid {
    int cells_per_axis = 1024;  ///< n, >= 2 and even (so v = 0 is a cell edge)
    double tail_sigmas = 8;     ///< Gaussian cut-off: exp(-8^2/2) ~ 1e-14 of the peak
};

/// Accuracy and coverage of a Fourier-domain filter against the double wedge.
struct FilterMetrics {
    double accuracy = 0;         ///< alpha, MAAF Eq. 14 (1 = no L2 error over T)
    double coverage = 0;         ///< gamma, MAAF Eq. 15 (1 = no filter outside T)
    double filter_integral = 0;  ///< the integral of |W| over the plane (MAAF Eq. 15's denominator)
};

/// alpha (MAAF Eq. 14) and gamma (MAAF Eq. 15) of `filter` for `wedge`, integrated
/// numerically on `grid`. Throws aaf::Error for a bad wedge or grid.
/// Independent of the thread count (rows summed in a fixed order).
FilterMetrics integrate_filter_metrics(const SpectralFilter &filter, const DoubleWedge &wedge,
                                       const WedgeIntegrationGrid &grid = {});

/// Coverage of AAF's box (MAAF Eq. 16) with the box's area from its geometry,
/// (2 Omega_y^max / s_min)(2 Omega_y^max): gamma = (1 - s_min/s_max) / 4.
double aaf_box_coverage(const DoubleWedge &wedge);

/// Coverage of FSF's tight parallelogram (MAAF Eq. 16): 1/2.
double fsf_box_coverage();

/// Total area of MAAF's 2N - 1 boxes (MAAF Eq. 17) with the central box's
/// area from MAAF Eq. 8, 4 sigma_x^0 sigma_y^0 = 4 (Omega_y^max/(2N-1))^2 / s_min.
double maaf_box_area(const DoubleWedge &wedge, int pairs);

/// Coverage of MAAF's 2N - 1 boxes (MAAF Eq. 18) with the central term of
/// maaf_box_area; N = 1 gives aaf_box_coverage.
double maaf_box_coverage(const DoubleWedge &wedge, int pairs);

/// MAAF Eq. 16 for AAF as printed, from the box area 4 (Omega_y^max / s_min)^2:
/// (s_min / 4)(1 - s_min/s_max), s_min times aaf_box_coverage.
double aaf_box_coverage_as_printed(const DoubleWedge &wedge);

/// MAAF Eq. 18 as printed, with 1/s_min^2 in the central term (MAAF Eq. 17's AAF box area).
double maaf_box_coverage_as_printed(const DoubleWedge &wedge, int pairs);

}  // namespace aaf
