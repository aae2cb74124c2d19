#include <tbb/global_control.h>
#include <tbb/task_arena.h>

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

TEST_CASE("Wedge: MAAF Eq. 18 (central box 4 sigma_x^0 sigma_y^0) equals the integrated MAAF box coverage",
          "[wedge][box]") {
    const int cells = 1024;
    for (const DoubleWedge &wedge : test_wedges())
        for (int pairs : {1, 2, 3, 4, 13}) {
            CAPTURE(wedge.s_min, wedge.s_max, pairs);
            const SpectralFilter filter = aaf::maaf_spectral_filter(wedge, pairs, SpectralShape::Box);
            CHECK(filter.integral() ==
                  Approx(aaf::maaf_box_area(wedge, pairs)).epsilon(1e-12));  // MAAF Eq. 17
            const aaf::FilterMetrics m = aaf::integrate_filter_metrics(filter, wedge, grid_of(cells));
            const double expected = aaf::maaf_box_coverage(wedge, pairs);
            CHECK(std::abs(m.coverage - expected) <=
                  expected * box_area_error_bound(filter, cells) / filter.integral());
            // The boxes hold all of T and do not overlap inside it: W = 1 there.
            CHECK(m.accuracy == Approx(1.0).margin(1e-12));
        }
    // MAAF Eq. 18 as printed (1/s_min^2 in the central term) is refused by the integral where s_min is far
    // from 1.
    for (const DoubleWedge &wedge : {DoubleWedge{0.2, 9.0, 1}, DoubleWedge{4.0, 9.5, 1}}) {
        const SpectralFilter filter = aaf::maaf_spectral_filter(wedge, 3, SpectralShape::Box);
        const double measured = aaf::integrate_filter_metrics(filter, wedge, grid_of(cells)).coverage;
        const double printed = aaf::maaf_box_coverage_as_printed(wedge, 3);
        CHECK(std::abs(measured - printed) >
              10 * printed * box_area_error_bound(filter, cells) / filter.integral());
    }
}

TEST_CASE("Wedge: MAAF with N = 1 is AAF's filter, for boxes and Gaussians", "[wedge]") {
    for (const SpectralShape shape : {SpectralShape::Box, SpectralShape::Gaussian})
        for (const DoubleWedge &wedge : test_wedges()) {
            const SpectralFilter maaf = aaf::maaf_spectral_filter(wedge, 1, shape);
            const SpectralFilter aaf_filter = aaf::aaf_spectral_filter(wedge, shape);
            REQUIRE(maaf.components.size() == 1);
            CHECK(maaf.components[0].center_x == 0);
            CHECK(maaf.components[0].center_y == 0);
            CHECK(maaf.components[0].width_x == Approx(aaf_filter.components[0].width_x).epsilon(1e-14));
            CHECK(maaf.components[0].width_y == Approx(aaf_filter.components[0].width_y).epsilon(1e-14));
            CHECK(maaf.components[0].weight == Approx(1.0).epsilon(1e-14));
            const aaf::FilterMetrics a = aaf::integrate_filter_metrics(maaf, wedge, grid_of(256));
            const aaf::FilterMetrics b = aaf::integrate_filter_metrics(aaf_filter, wedge, grid_of(256));
            CHECK(a.coverage == Approx(b.coverage).epsilon(1e-12));
            CHECK(a.accuracy == Approx(b.accuracy).epsilon(1e-12));
        }
    for (const DoubleWedge &wedge : test_wedges())
        CHECK(aaf::maaf_box_coverage(wedge, 1) == Approx(aaf::aaf_box_coverage(wedge)));
}

TEST_CASE("Wedge: MAAF box coverage rises toward 1 with N", "[wedge][box]") {
    for (const DoubleWedge &wedge : test_wedges()) {
        CAPTURE(wedge.s_min, wedge.s_max);
        double previous = 0;
        for (int pairs = 1; pairs <= 400; ++pairs) {
            const double coverage = aaf::maaf_box_coverage(wedge, pairs);
            CHECK(coverage > previous);
            CHECK(coverage < 1.0);
            previous = coverage;
        }
        // MAAF Eq. 18's limit: 1 / (1 + O(1/N)), so at N = 400 within 1/N of 1 times the wedge's ratio term.
        const double ratio_term = (1 / wedge.s_min + 1 / wedge.s_max) / (1 / wedge.s_min - 1 / wedge.s_max);
        CHECK(1.0 - previous < 1.5 * ratio_term / 400);
        // The integrated coverage rises too.
        double integrated_previous = 0;
        for (int pairs : {1, 2, 3, 4, 13}) {
            const double c =
                aaf::integrate_filter_metrics(aaf::maaf_spectral_filter(wedge, pairs, SpectralShape::Box),
                                              wedge, grid_of(512))
                    .coverage;
            CHECK(c > integrated_previous);
            integrated_previous = c;
        }
    }
}

TEST_CASE("Wedge: the integration converges as the grid is refined", "[wedge][convergence]") {
    const DoubleWedge wedge{0.7, 2.2, 1};
    SECTION("boxes: the error to MAAF Eq. 18 stays under its O(1/n) bound at every grid") {
        const SpectralFilter filter = aaf::maaf_spectral_filter(wedge, 3, SpectralShape::Box);
        const double exact = aaf::maaf_box_coverage(wedge, 3);
        for (int cells : {64, 128, 256, 512, 1024, 2048, 4096}) {
            CAPTURE(cells);
            const double error =
                std::abs(aaf::integrate_filter_metrics(filter, wedge, grid_of(cells)).coverage - exact);
            CHECK(error <= exact * box_area_error_bound(filter, cells) / filter.integral());
        }
    }
    SECTION("Gaussians: successive refinements change the result less and less") {
        for (int pairs : {1, 3}) {
            const SpectralFilter filter = aaf::maaf_spectral_filter(wedge, pairs, SpectralShape::Gaussian);
            std::vector<aaf::FilterMetrics> m;
            for (int cells : {64, 128, 256, 512, 1024})
                m.push_back(aaf::integrate_filter_metrics(filter, wedge, grid_of(cells)));
            for (std::size_t k = 2; k < m.size(); ++k) {
                CAPTURE(pairs, k);
                // Second order (the wedge grid's midpoint rule on a smooth integrand): /4 per halving.
                CHECK(std::abs(m[k].coverage - m[k - 1].coverage) <
                      0.35 * std::abs(m[k - 1].coverage - m[k - 2].coverage) + 1e-12);
                CHECK(std::abs(m[k].accuracy - m[k - 1].accuracy) <
                      0.35 * std::abs(m[k - 1].accuracy - m[k - 2].accuracy) + 1e-12);
            }
            CHECK(m.back().filter_integral == Approx(filter.integral()).epsilon(1e-9));
        }
    }
}

TEST_CASE(
    "Wedge: Gaussian MAAF is MAAF Eq. 9 with mu_p of MAAF Eq. 10 and covers more of T than AAF and FSF on "
    "the Table 2 "
    "wedges",
    "[wedge][gaussian]") {
    for (const DoubleWedge &wedge :
         {DoubleWedge{0.5, 0.8, 1}, DoubleWedge{1.5, 2.0, 1}, DoubleWedge{0.7, 2.2, 1}}) {
        CAPTURE(wedge.s_min, wedge.s_max);
        const SpectralFilter maaf = aaf::maaf_spectral_filter(wedge, 3, SpectralShape::Gaussian);
        REQUIRE(maaf.components.size() == 5);
        for (const aaf::SpectralComponent &c : maaf.components) {
            // MAAF Eq. 10 with peak-1 Gaussians: mu_p = G(C_x; W/s_min) G(C_y; W).
            const double sx = wedge.omega_y_max / wedge.s_min, sy = wedge.omega_y_max;
            CHECK(c.weight == Approx(std::exp(-0.5 * (c.center_x * c.center_x / (sx * sx) +
                                                      c.center_y * c.center_y / (sy * sy)))));
        }
        const auto metrics = [&](const SpectralFilter &f) {
            return aaf::integrate_filter_metrics(f, wedge, grid_of(512));
        };
        const aaf::FilterMetrics m = metrics(maaf);
        const aaf::FilterMetrics a = metrics(aaf::aaf_spectral_filter(wedge, SpectralShape::Gaussian));
        CHECK(m.coverage > a.coverage);
        CHECK(m.coverage > metrics(aaf::fsf_spectral_filter(wedge, SpectralShape::Gaussian)).coverage);
        CHECK(m.accuracy <= 1);
    }
}

TEST_CASE("Wedge: the metrics do not depend on the thread count", "[wedge]") {
    const DoubleWedge wedge{0.7, 2.2, 1};
    const SpectralFilter filter = aaf::maaf_spectral_filter(wedge, 3, SpectralShape::Gaussian);
    const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
    aaf::FilterMetrics one, three;
    tbb::task_arena(1).execute([&] { one = aaf::integrate_filter_metrics(filter, wedge, grid_of(256)); });
    tbb::task_arena(3).execute([&] { three = aaf::integrate_filter_metrics(filter, wedge, grid_of(256)); });
    CHECK(one.coverage == three.coverage);
    CHECK(one.accuracy == three.accuracy);
}
