#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/analysis/spectral_filter.h"
#include "aaf/core/analysis/wedge_metrics.h"
#include "aaf/core/analysis/wedge_spectrum.h"

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
/// the n x n grid (cells hx by hy) of the filter's bounding rectangle: along
/// a row, the cells counted inside an interval of length L number L/hx +- 1,
/// and the rows inside a box (Ly/hy +- 1), so each box (or parallelogram) is
/// off by at most Lx hy + Ly hx + hx hy.
inline double box_area_error_bound(const aaf::SpectralFilter &filter, int cells) {
    double x_half = 0, y_half = 0;
    for (const aaf::SpectralComponent &c : filter.components) {
        y_half = std::max(y_half, std::abs(c.center_y) + c.width_y);
        x_half = std::max(x_half, std::abs(c.center_x) + std::abs(c.shear) * c.width_y + c.width_x);
    }
    const double hx = 2 * x_half / cells, hy = 2 * y_half / cells;
    double bound = 0;
    for (const aaf::SpectralComponent &c : filter.components)
        bound += 2 * c.width_x * hy + 2 * c.width_y * hx + hx * hy;
    return bound;
}

}  // namespace wedge_test
