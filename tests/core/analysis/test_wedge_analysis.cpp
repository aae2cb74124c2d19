#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "aaf/core/analysis/spectral_filter.h"
#include "aaf/core/analysis/wedge_metrics.h"
#include "aaf/core/analysis/wedge_spectrum.h"
#include "aaf/core/util/error.h"
#include "wedge_test_helpers.h"

using aaf::DoubleWedge;
using aaf::SpectralFilter;
using aaf::SpectralShape;
using aaf::WedgeIntegrationGrid;

using wedge_test::box_area_error_bound;
using wedge_test::grid_of;
using wedge_test::kPi;
using wedge_test::test_wedges;

TEST_CASE("Wedge: membership and area match the geometry of MAAF Fig. 4", "[wedge]") {
    const DoubleWedge wedge{1.0, 2.0, 1.0};
    // At Omega_y = 1 the wedge spans Omega_x in [1/2, 1]; at -1, [-1, -1/2].
    CHECK(aaf::in_double_wedge(wedge, 0.75, 1.0));
    CHECK(aaf::in_double_wedge(wedge, -0.75, -1.0));
    CHECK_FALSE(aaf::in_double_wedge(wedge, 0.4, 1.0));
    CHECK_FALSE(aaf::in_double_wedge(wedge, 0.75, -1.0));
    CHECK_FALSE(aaf::in_double_wedge(wedge, 0.75, 1.01));
    CHECK(aaf::double_wedge_area(wedge) == Approx(0.5));  // two triangles of height 1, base 1/2
    CHECK(aaf::double_wedge_area({1.0, 2.0, 3.0}) == Approx(4.5));
    CHECK_THROWS_AS(aaf::check_double_wedge({2.0, 2.0, 1.0}), aaf::Error);
    CHECK_THROWS_AS(aaf::check_double_wedge({0.0, 2.0, 1.0}), aaf::Error);
    CHECK_THROWS_AS(aaf::check_double_wedge({1.0, 2.0, 0.0}), aaf::Error);
}

TEST_CASE("Wedge: MAAF Eq. 16 from the boxes' geometry equals the integrated AAF and FSF box coverage",
          "[wedge][box]") {
    const int cells = 1024;
    for (const DoubleWedge &wedge : test_wedges()) {
        CAPTURE(wedge.s_min, wedge.s_max);
        for (const bool aaf_method : {true, false}) {
            const SpectralFilter filter = aaf_method ? aaf::aaf_spectral_filter(wedge, SpectralShape::Box)
                                                     : aaf::fsf_spectral_filter(wedge, SpectralShape::Box);
            const aaf::FilterMetrics m = aaf::integrate_filter_metrics(filter, wedge, grid_of(cells));
            const double expected = aaf_method ? aaf::aaf_box_coverage(wedge) : aaf::fsf_box_coverage();
            // coverage = |T| / area; the area is off by at most the bound.
            const double tolerance = expected * box_area_error_bound(filter, cells) / filter.integral();
            CHECK(std::abs(m.coverage - expected) <= tolerance);
            CHECK(m.accuracy == Approx(1.0).margin(1e-12));  // the box holds all of T
        }
    }
}

TEST_CASE("Wedge: the printed MAAF Eq. 16 and 18 are s_min times off in the central box, the integral is not",
          "[wedge][box]") {
    // The printed AAF box area 4 (Omega_y^max / s_min)^2 has units Omega_x^2 where an area in the
    // (Omega_x, Omega_y) plane has Omega_x Omega_y; the printed coverage scales with s_min.
    for (const DoubleWedge &wedge : test_wedges()) {
        CAPTURE(wedge.s_min, wedge.s_max);
        CHECK(aaf::aaf_box_coverage_as_printed(wedge) == Approx(wedge.s_min * aaf::aaf_box_coverage(wedge)));
        CHECK(aaf::maaf_box_coverage_as_printed(wedge, 1) == Approx(aaf::aaf_box_coverage_as_printed(wedge)));
    }
    // Where s_min = 1 the two agree; at s_min = 0.5 the integral sides with the geometry.
    CHECK(aaf::maaf_box_coverage_as_printed({1.0, 3.0, 1}, 3) ==
          Approx(aaf::maaf_box_coverage({1.0, 3.0, 1}, 3)));
    const DoubleWedge wedge{0.5, 0.8, 1};
    const double measured =
        aaf::integrate_filter_metrics(aaf::aaf_spectral_filter(wedge, SpectralShape::Box), wedge).coverage;
    CHECK(measured == Approx(0.09375).epsilon(1e-6));  // (1 - 0.5/0.8) / 4
    CHECK(aaf::aaf_box_coverage_as_printed(wedge) == Approx(0.046875));
    // Coverage of a box of the wedge's own scale cannot exceed 1; the printed form does for large s_min.
    CHECK(aaf::aaf_box_coverage_as_printed({40.0, 1000.0, 1}) > 1.0);
    CHECK(aaf::aaf_box_coverage({40.0, 1000.0, 1}) < 0.25);
}

TEST_CASE("Wedge: Gaussian AAF coverage matches a 1D quadrature of the erf form", "[wedge][gaussian]") {
    // gamma = int_{-W}^{W} G(Oy; W) int_{Oy/smax}^{Oy/smin} G(Ox; W/smin) dOx dOy / (2 pi W W/smin),
    // the inner integral in closed form with erf, the outer by Simpson's rule on 20000 intervals.
    for (const DoubleWedge &wedge : test_wedges()) {
        CAPTURE(wedge.s_min, wedge.s_max);
        const double w = wedge.omega_y_max, sx = w / wedge.s_min;
        const auto inner = [&](double oy) {
            const double a = oy / wedge.s_max, b = oy / wedge.s_min;
            return sx * std::sqrt(kPi / 2) *
                   std::abs(std::erf(b / (sx * std::sqrt(2.0))) - std::erf(a / (sx * std::sqrt(2.0))));
        };
        const int steps = 20000;
        double sum = 0;
        for (int k = 0; k <= steps; ++k) {
            const double oy = -w + 2 * w * k / steps;
            const double simpson = (k == 0 || k == steps) ? 1 : (k % 2 ? 4 : 2);
            sum += simpson * std::exp(-0.5 * oy * oy / (w * w)) * inner(oy);
        }
        const double reference = sum * (2 * w / steps) / 3 / (2 * kPi * w * sx);
        const aaf::FilterMetrics m =
            aaf::integrate_filter_metrics(aaf::aaf_spectral_filter(wedge, SpectralShape::Gaussian), wedge);
        CHECK(m.coverage == Approx(reference).epsilon(1e-5));
    }
}

TEST_CASE("Wedge: random wedges are sorted uniform pairs in (0, 10), the same for a seed",
          "[wedge][random]") {
    const std::vector<DoubleWedge> a = aaf::uniform_sorted_wedges(20000, 7),
                                   b = aaf::uniform_sorted_wedges(20000, 7);
    REQUIRE(a.size() == 20000);
    double ratio_sum = 0, max_sum = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        CHECK((a[k].s_min == b[k].s_min && a[k].s_max == b[k].s_max));
        CHECK((0 < a[k].s_min && a[k].s_min < a[k].s_max && a[k].s_max < 10));
        ratio_sum += a[k].s_min / a[k].s_max;
        max_sum += a[k].s_max;
    }
    // For a sorted uniform pair, s_min/s_max is uniform on (0, 1) (mean 1/2, sd 0.289) and
    // E[s_max] = 20/3 (sd 2.36): 5 standard errors of 20000 draws.
    CHECK(std::abs(ratio_sum / 20000 - 0.5) < 5 * 0.289 / std::sqrt(20000.0));
    CHECK(std::abs(max_sum / 20000 - 20.0 / 3) < 5 * 2.36 / std::sqrt(20000.0));
    CHECK(aaf::uniform_sorted_wedges(3, 8)[0].s_min != a[0].s_min);
}
