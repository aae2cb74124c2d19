#include "aaf/core/analysis/wedge_metrics.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

/// W along one row Omega_y of the plane, evaluated at many Omega_x: the
/// components' Omega_y factors are computed once, and components whose
/// factor is 0 (beyond a box edge or the Gaussian cut-off) are skipped.
class FilterRow {
  public:
    FilterRow(const SpectralFilter &filter, double tail_sigmas, double omega_y)
        : filter_(filter), reach_(filter.shape == SpectralShape::Box ? 1.0 : tail_sigmas) {
        for (const SpectralComponent &c : filter.components) {
            const double u = (omega_y - c.center_y) / c.width_y;
            if (std::abs(u) > reach_) continue;
            active_.push_back({&c, c.weight * spectral_profile(filter.shape, u),
                               c.center_x + c.shear * (omega_y - c.center_y)});
        }
    }

    double value(double omega_x) const {
        double sum = 0;
        for (const Active &a : active_) {
            const double u = (omega_x - a.center_x) / a.component->width_x;
            if (std::abs(u) <= reach_) sum += a.factor_y * spectral_profile(filter_.shape, u);
        }
        return sum;
    }

  private:
    struct Active {
        const SpectralComponent *component;
        double factor_y;  // weight * P(Omega_y)
        double center_x;  // the component's Omega_x centre on this row (sheared)
    };
    const SpectralFilter &filter_;
    double reach_;  // |u| beyond which a profile counts as 0
    std::vector<Active> active_;
};

void check_grid(const WedgeIntegrationGrid &grid) {
    if (grid.cells_per_axis < 2 || grid.cells_per_axis % 2 != 0)
        throw Error("integration grid needs an even number of cells >= 2, got " +
                    std::to_string(grid.cells_per_axis));
    if (!(std::isfinite(grid.tail_sigmas) && grid.tail_sigmas > 0))
        throw Error("Gaussian cut-off must be > 0 standard deviations, got " +
                    std::to_string(grid.tail_sigmas));
}

void check_filter(const SpectralFilter &filter) {
    if (filter.components.empty()) throw Error("spectral filter has no components");
    for (const SpectralComponent &c : filter.components)
        if (!(c.width_x > 0 && c.width_y > 0 && std::isfinite(c.width_x) && std::isfinite(c.width_y) &&
              std::isfinite(c.weight) && std::isfinite(c.center_x) && std::isfinite(c.center_y) &&
              std::isfinite(c.shear)))
            throw Error("spectral filter component needs finite values and widths > 0");
}

void check_pairs(int pairs) {
    if (pairs < 1) throw Error("MAAF needs N >= 1 component pairs, got " + std::to_string(pairs));
}

}  // namespace

FilterMetrics integrate_filter_metrics(const SpectralFilter &filter, const DoubleWedge &wedge,
                                       const WedgeIntegrationGrid &grid) {
    check_double_wedge(wedge);
    check_grid(grid);
    check_filter(filter);
    const int n = grid.cells_per_axis;
    const double w_max = wedge.omega_y_max, spread = 1.0 / wedge.s_min - 1.0 / wedge.s_max;

    // Over T, in wedge coordinates (v, t); per-row sums, added in row order below.
    std::vector<double> row_area(n), row_filter(n), row_error(n);
    parallel_for_rows(n, [&](int j) {
        const double v = -1.0 + (j + 0.5) * (2.0 / n);
        const double omega_y = w_max * v;
        const double cell = (2.0 / n) * (1.0 / n) * w_max * w_max * std::abs(v) * spread;  // Jacobian
        const FilterRow row(filter, grid.tail_sigmas, omega_y);
        double filter_sum = 0, error_sum = 0;
        for (int i = 0; i < n; ++i) {
            const double t = (i + 0.5) / n;
            const double w = row.value(omega_y * (1.0 / wedge.s_max + t * spread));
            filter_sum += std::abs(w);           // MAAF Eq. 15 numerator
            error_sum += (w - 1.0) * (w - 1.0);  // MAAF Eq. 14 numerator, T = 1 on its support
        }
        row_area[j] = cell * n;
        row_filter[j] = cell * filter_sum;
        row_error[j] = cell * error_sum;
    });

    // Over the filter's bounding rectangle.
    const double reach = filter.shape == SpectralShape::Box ? 1.0 : grid.tail_sigmas;
    double x_half = 0, y_half = 0;
    for (const SpectralComponent &c : filter.components) {
        // On a row, a sheared component's Omega_x centre moves by shear (Omega_y - C_y).
        y_half = std::max(y_half, std::abs(c.center_y) + reach * c.width_y);
        x_half = std::max(x_half,
                          std::abs(c.center_x) + std::abs(c.shear) * reach * c.width_y + reach * c.width_x);
    }
    const double dx = 2.0 * x_half / n, dy = 2.0 * y_half / n;
    std::vector<double> row_total(n);
    parallel_for_rows(n, [&](int j) {
        const FilterRow row(filter, grid.tail_sigmas, -y_half + (j + 0.5) * dy);
        double sum = 0;
        for (int i = 0; i < n; ++i) sum += std::abs(row.value(-x_half + (i + 0.5) * dx));
        row_total[j] = sum * dx * dy;
    });

    double area = 0, in_wedge = 0, error = 0, total = 0;
    for (int j = 0; j < n; ++j) {
        area += row_area[j];
        in_wedge += row_filter[j];
        error += row_error[j];
        total += row_total[j];
    }
    FilterMetrics metrics;
    metrics.accuracy = 1.0 - std::sqrt(error / area);       // MAAF Eq. 14
    metrics.coverage = total > 0 ? in_wedge / total : 0.0;  // MAAF Eq. 15
    metrics.filter_integral = total;
    return metrics;
}

double aaf_box_coverage(const DoubleWedge &wedge) {
    check_double_wedge(wedge);
    // MAAF Eq. 16 with the box (2 Omega_y^max/s_min) x (2 Omega_y^max) of MAAF Eq. 2's extents.
    return double_wedge_area(wedge) / (4.0 * wedge.omega_y_max * wedge.omega_y_max / wedge.s_min);
}

double fsf_box_coverage() {
    return 0.5;  // MAAF Eq. 16: the parallelogram 2 (Omega_y^max)^2 (1/s_min - 1/s_max) is twice T
}

double maaf_box_area(const DoubleWedge &wedge, int pairs) {
    check_double_wedge(wedge);
    check_pairs(pairs);
    const double n = pairs, side = wedge.omega_y_max / (2.0 * n - 1.0);
    const double spread = 1.0 / wedge.s_min - 1.0 / wedge.s_max;
    const double inv_s_avg = 0.5 * (1.0 / wedge.s_min + 1.0 / wedge.s_max);
    // MAAF Eq. 17, central term 4 sigma_x^0 sigma_y^0 / side^2 = 1/s_min (MAAF Eq. 8), pairs summed:
    // sum_{p=1}^{N-1} [p spread + 1/s_avg] = N(N-1)/2 spread + (N-1)/s_avg.
    return 4.0 * side * side * (1.0 / wedge.s_min + n * (n - 1.0) * spread + 2.0 * (n - 1.0) * inv_s_avg);
}

double maaf_box_coverage(const DoubleWedge &wedge, int pairs) {
    check_double_wedge(wedge);
    check_pairs(pairs);
    const double n = pairs, half = (n - 0.5) * (n - 0.5);
    const double spread = 1.0 / wedge.s_min - 1.0 / wedge.s_max;
    const double inv_s_avg = 0.5 * (1.0 / wedge.s_min + 1.0 / wedge.s_max);
    // MAAF Eq. 18 with 1/s_min for the printed 1/s_min^2 (see maaf_box_area).
    return 1.0 / (n * (n - 1.0) / half + (1.0 / wedge.s_min + 2.0 * (n - 1.0) * inv_s_avg) / (spread * half));
}

double aaf_box_coverage_as_printed(const DoubleWedge &wedge) {
    check_double_wedge(wedge);
    return wedge.s_min / 4.0 * (1.0 - wedge.s_min / wedge.s_max);  // MAAF Eq. 16 as printed
}

double maaf_box_coverage_as_printed(const DoubleWedge &wedge, int pairs) {
    check_double_wedge(wedge);
    check_pairs(pairs);
    const double n = pairs, half = (n - 0.5) * (n - 0.5);
    const double spread = 1.0 / wedge.s_min - 1.0 / wedge.s_max;
    const double inv_s_avg = 0.5 * (1.0 / wedge.s_min + 1.0 / wedge.s_max);
    const double central = 1.0 / (wedge.s_min * wedge.s_min);  // MAAF Eq. 18 as printed
    return 1.0 / (n * (n - 1.0) / half + (central + 2.0 * (n - 1.0) * inv_s_avg) / (spread * half));
}

}  // namespace aaf
