#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "aaf/core/methods/maaf/maaf_components.h"
#include "aaf/core/util/error.h"

using aaf::maaf_components;
using aaf::maaf_pair_components;
using aaf::MaafComponent;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

bool all_finite(const std::vector<MaafComponent> &components) {
    for (const MaafComponent &c : components)
        for (double v : {c.centre_x, c.centre_y, c.sigma_x, c.sigma_y, c.weight})
            if (!std::isfinite(v)) return false;
    return true;
}
}  // namespace

TEST_CASE("MAAF components match hand-computed MAAF Eq. 6-10 for N = 2", "[maaf][components]") {
    // s_min = 1, s_max = 3, Omega_y^max = 10 rad/m, no pixel clip; 2N - 1 = 3 slices.
    // Omega_y^max / s_min = 10, Omega_y^max / s_max = 10/3.
    const auto c = maaf_components(1.0, 3.0, kInf, 10.0, 2);
    REQUIRE(c.size() == 3);
    CHECK(c[0].index == -1);
    CHECK(c[1].index == 0);
    CHECK(c[2].index == 1);
    // p = 0: C = (0, 0), sigma_y = 10/3, sigma_x^0 = (10/1)/3, mu_0 = 1.
    CHECK(c[1].sign == 0);
    CHECK(c[1].centre_x == 0.0);
    CHECK(c[1].centre_y == 0.0);
    CHECK(c[1].sigma_x == Approx(10.0 / 3.0));
    CHECK(c[1].sigma_y == Approx(10.0 / 3.0));
    CHECK(c[1].weight == Approx(1.0));
    // p = 1: C_y = 10 * 2/3 (MAAF Eq. 6); C_x = 1/2 (10/3 * 1/3 + 10 * 3/3) = 50/9 (MAAF Eq. 7);
    // sigma_x = 1/2 (10 * 3/3 - 10/3 * 1/3) = 40/9 (MAAF Eq. 8);
    // mu = exp(-(50/9)^2 / 200) exp(-(20/3)^2 / 200) = exp(-0.3765432) (MAAF Eq. 10).
    CHECK(c[2].sign == 1);
    CHECK(c[2].centre_y == Approx(20.0 / 3.0));
    CHECK(c[2].centre_x == Approx(50.0 / 9.0));
    CHECK(c[2].sigma_x == Approx(40.0 / 9.0));
    CHECK(c[2].sigma_y == Approx(10.0 / 3.0));
    CHECK(c[2].weight == Approx(std::exp(-0.37654321)).epsilon(1e-7));
    // The pair's other member is the mirror image (MAAF Eq. 7's symmetry).
    CHECK(c[0].sign == -1);
    CHECK(c[0].centre_x == Approx(-c[2].centre_x));
    CHECK(c[0].centre_y == Approx(-c[2].centre_y));
    CHECK(c[0].sigma_x == Approx(c[2].sigma_x));
    CHECK(c[0].weight == Approx(c[2].weight));
}

TEST_CASE("MAAF with N = 1 is AAF's single filter (MAAF Eq. 2), clipped by the pixel band-limit",
          "[maaf][components]") {
    const auto free = maaf_components(0.5, 2.0, kInf, 4.0, 1);
    REQUIRE(free.size() == 1);
    CHECK(free[0].sigma_x == Approx(4.0 / 0.5));  // Omega_y^max / s_min
    CHECK(free[0].sigma_y == Approx(4.0));
    CHECK(free[0].centre_x == 0.0);
    CHECK(free[0].weight == 1.0);
    // Omega_x^max = 5 < 8: AAF Eq. 8's min(), and Omega_y^max is lowered to s_min Omega_x^max (Sec. 6.2).
    const auto clipped = maaf_components(0.5, 2.0, 5.0, 4.0, 1);
    CHECK(clipped[0].sigma_x == Approx(5.0));
    CHECK(clipped[0].sigma_y == Approx(2.5));
    CHECK(aaf::maaf_partitioned_omega_y_max(0.5, 2.0, 5.0, 4.0) == Approx(2.5));
}

TEST_CASE("Each MAAF box spans exactly its slice of the double wedge", "[maaf][components]") {
    // Read as boxes (Sec. 5), component p >= 1 spans Omega_y in [(2p-1), (2p+1)] Omega/(2N-1) and
    // Omega_x from the s_max edge at its lower Omega_y to the s_min edge at its upper Omega_y.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> slope(0.05, 10.0);
    for (int trial = 0; trial < 50; ++trial) {
        double a = slope(rng), b = slope(rng);
        if (a > b) std::swap(a, b);
        for (int n : {2, 3, 4, 7}) {
            const double omega = 3.0, q = 2.0 * n - 1.0;
            for (const MaafComponent &c : maaf_pair_components(a, b, kInf, omega, n)) {
                if (c.index == 0) continue;
                const int p = c.index;
                CHECK(c.centre_y - c.sigma_y == Approx(omega * (2 * p - 1) / q));
                CHECK(c.centre_y + c.sigma_y == Approx(omega * (2 * p + 1) / q));
                CHECK(c.centre_x - c.sigma_x == Approx(omega * (2 * p - 1) / q / b));
                CHECK(c.centre_x + c.sigma_x == Approx(omega * (2 * p + 1) / q / a));
                CHECK(c.weight > 0);
                CHECK(c.weight < 1);
            }
        }
    }
}

TEST_CASE("Degenerate MAAF wedges give finite components", "[maaf][components]") {
    SECTION("s_min = s_max: a line, every box as wide as the slice's x extent") {
        const auto c = maaf_components(2.0, 2.0, kInf, 6.0, 3);
        REQUIRE(all_finite(c));
        for (const MaafComponent &m : c) CHECK(m.sigma_x == Approx(6.0 / 5.0 / 2.0));
        // centres lie on the line Omega_x = Omega_y / s
        for (const MaafComponent &m : c) CHECK(m.centre_x == Approx(m.centre_y / 2.0).margin(1e-12));
    }
    SECTION("s_min = 0 (contact): the pixel band-limit bounds the wedge") {
        const auto c = maaf_components(0.0, 1.0, 50.0, 6.0, 3);
        REQUIRE(all_finite(c));
        for (const MaafComponent &m : c) {
            CHECK(m.centre_y == 0.0);
            CHECK(m.sigma_y == 0.0);
        }
        CHECK(c[2].sigma_x == Approx(50.0 / 5.0));
        const auto both_zero = maaf_components(0.0, 0.0, 50.0, 6.0, 3);
        CHECK(all_finite(both_zero));
    }
    SECTION("s_max = inf (occluder at the light)") {
        CHECK(all_finite(maaf_components(0.5, kInf, kInf, 6.0, 3)));
    }
}

TEST_CASE("MAAF components refuse arguments without a wedge", "[maaf][components]") {
    CHECK_THROWS_AS(maaf_components(1.0, 2.0, kInf, 1.0, 0), aaf::Error);
    CHECK_THROWS_AS(maaf_components(2.0, 1.0, kInf, 1.0, 3), aaf::Error);
    CHECK_THROWS_AS(maaf_components(-1.0, 1.0, kInf, 1.0, 3), aaf::Error);
    CHECK_THROWS_AS(maaf_components(std::nan(""), 1.0, kInf, 1.0, 3), aaf::Error);
    CHECK_THROWS_AS(maaf_components(1.0, 2.0, kInf, 0.0, 3), aaf::Error);
    CHECK_THROWS_AS(maaf_components(1.0, 2.0, 0.0, 1.0, 3), aaf::Error);
    CHECK_THROWS_AS(maaf_components(0.0, 2.0, kInf, 1.0, 3), aaf::Error);
}

TEST_CASE("MAAF Eq. 9 sums the weighted components", "[maaf][components]") {
    const auto c = maaf_components(1.0, 3.0, kInf, 10.0, 2);
    // At the centre of component 1 it contributes mu_1; the others their Gaussian tails.
    const double at = aaf::maaf_fourier_filter(c, c[2].centre_x, c[2].centre_y);
    const double from_centre = std::exp(-std::pow(c[2].centre_x / c[1].sigma_x, 2) / 2) *
                               std::exp(-std::pow(c[2].centre_y / c[1].sigma_y, 2) / 2);
    const double from_mirror = c[0].weight * std::exp(-std::pow(2 * c[2].centre_x / c[0].sigma_x, 2) / 2) *
                               std::exp(-std::pow(2 * c[2].centre_y / c[0].sigma_y, 2) / 2);
    CHECK(at == Approx(c[2].weight + from_centre + from_mirror));
    CHECK(aaf::maaf_fourier_filter(c, 0, 0) ==
          Approx(1.0 + 2 * c[2].weight * std::exp(-std::pow(c[2].centre_x / c[2].sigma_x, 2) / 2) *
                           std::exp(-std::pow(c[2].centre_y / c[2].sigma_y, 2) / 2)));
}
