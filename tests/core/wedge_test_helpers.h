#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/spectral_filter.h"
#include "aaf/core/wedge_metrics.h"
#include "aaf/core/wedge_spectrum.h"

/// Shared by the wedge-analysis tests (test_wedge_analysis.cpp, test_wedge_maaf.cpp).
namespace wedge_test {

inline constexpr double kPi = 3.14159265358979323846;

inline aaf::WedgeIntegrationGrid grid_of(int cells) {
    aaf::WedgeIntegrationGrid grid;
    grid.cells_per_axis = cells;
    return grid;
}

/// The wedges the tests try: the three of MAAF Table 2, a narrow one, a wide
/// one with s_min < 1 and one with both slopes large.
inline const std::vector<aaf::DoubleWedge> &test_wedges() {
    static const std::vector<aaf::DoubleWedge> wedges = {{0.5, 0.8, 1}, {1.5, 2.0, 1}, {0.7, 2.2, 1},
                                                         {3.0, 3.3, 1}, {0.2, 9.0, 1}, {4.0, 9.5, 1}};
    return wedges;
}

/// A bound on the midpoint rule's error for the area of a union of boxes on
/// the n x n grid of the filter's bounding rectangle: each box edge is off by
/// at most a cell, so the area by at most (perimeter) x (cell diagonal).
inline double box_area_error_bound(const aaf::SpectralFilter &filter, int cells) {
    double x_half = 0, y_half = 0, perimeter = 0;
    for (const aaf::SpectralComponent &c : filter.components) {
        y_half = std::max(y_half, std::abs(c.center_y) + c.width_y);
        x_half = std::max(x_half, std::abs(c.center_x) + std::abs(c.shear) * c.width_y + c.width_x);
        // A sheared edge is longer than its Omega_y extent: sqrt(1 + shear^2) per unit.
        perimeter += 4 * c.width_x + 4 * c.width_y * std::sqrt(1 + c.shear * c.shear);
    }
    return perimeter * std::hypot(2 * x_half / cells, 2 * y_half / cells);
}

}  // namespace wedge_test
