// MAAF for combined effects (Wu et al. 2017, Sec. 6.2): the 3D partition,
// the 6D accumulation layout, the x kernels and the filter's per-pixel
// choices, against values computed by hand.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "aaf/core/methods/maaf/maaf_components.h"
#include "aaf/core/methods/maaf6/maaf6_components.h"
#include "aaf/core/methods/maaf6/maaf6_filter.h"
#include "maaf6_test_planes.h"

using namespace aaf;
using namespace aaf::maaf6_test;

TEST_CASE("MAAF 6D without a lens is the 2D partition of MAAF Eq. 6-10", "[maaf6]") {
    Maaf6Wedge w = example_wedge(0, 0);
    w.has_u = false;
    const std::vector<Maaf6Component> six = maaf6_pair_components(w, 3);
    const std::vector<MaafComponent> two = maaf_pair_components(1, 2, 1e6, 10, 3);
    REQUIRE(six.size() == 3);
    for (std::size_t p = 0; p < 3; ++p) {
        CHECK(six[p].centre_x == Approx(two[p].centre_x));
        CHECK(six[p].sigma_x == Approx(two[p].sigma_x));
        CHECK(six[p].centre_y == Approx(two[p].centre_y));
        CHECK(six[p].weight == Approx(two[p].weight));
        CHECK(six[p].centre_u == 0);
    }
}

TEST_CASE("MAAF 6D maps each component's x range through the u-wedge (Fig. 11c), by hand", "[maaf6]") {
    // Eq. 6-8 with Omega = 10, extents 10 / 1 and 10 / 2, 2N - 1 = 5:
    // p = 1: x in [1, 6]; p = 2: x in [3, 10]; p = 0: x in [-2, 2].
    const std::vector<Maaf6Component> c = maaf6_pair_components(example_wedge(0.5, 1.0), 3);
    CHECK(c[1].centre_x == Approx(3.5));
    CHECK(c[1].sigma_x == Approx(2.5));
    CHECK(c[1].centre_y == Approx(4));
    CHECK(c[1].centre_u == Approx(3.25));  // u in [0.5 * 1, 1.0 * 6]
    CHECK(c[1].sigma_u == Approx(2.75));
    CHECK(c[2].centre_x == Approx(6.5));
    CHECK(c[2].centre_y == Approx(8));
    CHECK(c[2].centre_u == Approx(5.75));  // u in [0.5 * 3, 1.0 * 10]
    CHECK(c[2].sigma_u == Approx(4.25));
    CHECK(c[0].sigma_x == Approx(2));
    CHECK(c[0].centre_u == Approx(0));
    CHECK(c[0].sigma_u == Approx(2));  // u in [-2, 2]
    // Slopes of both signs (the focal-plane box): p = 1's products -0.5, -3, 1, 6.
    const std::vector<Maaf6Component> box = maaf6_pair_components(example_wedge(-0.5, 1.0), 3);
    CHECK(box[1].centre_u == Approx(1.5));
    CHECK(box[1].sigma_u == Approx(4.5));
}

TEST_CASE("MAAF 6D lowers the x band to the u-wedge's and clips u to its band", "[maaf6]") {
    // One-signed u slopes [2, 4] with Omega_u^max 4: Omega_x <= 4 / 2 = 2, so Omega_y is clipped to 1 * 2.
    Maaf6Wedge w = example_wedge(2, 4);
    w.omega_u_max = 4;
    const std::vector<Maaf6Component> c = maaf6_pair_components(w, 3);
    const std::vector<MaafComponent> two = maaf_pair_components(1, 2, 2, 10, 3);
    for (std::size_t p = 0; p < 3; ++p) {
        CHECK(c[p].centre_x == Approx(two[p].centre_x));
        CHECK(c[p].centre_y == Approx(two[p].centre_y));
        CHECK(std::fabs(c[p].centre_u) + c[p].sigma_u <= 4 + 1e-9);
    }
}

TEST_CASE("MAAF 6D without a y-wedge partitions the u-wedge, the focal-plane box keeps the central filter",
          "[maaf6]") {
    Maaf6Wedge w = example_wedge(-1.0, -0.5);
    w.has_y = false;
    const std::vector<Maaf6Component> c = maaf6_pair_components(w, 3);
    const std::vector<MaafComponent> two = maaf_pair_components(0.5, 1.0, 1e6, 100, 3);
    for (std::size_t p = 0; p < 3; ++p) {
        CHECK(c[p].centre_x == Approx(two[p].centre_x));
        CHECK(c[p].centre_u == Approx(-two[p].centre_y));  // negative slopes: Omega_u = s Omega_x < 0
        CHECK(c[p].centre_y == 0);
    }
    w.u_min = -0.5;
    w.u_max = 1.0;
    const std::vector<Maaf6Component> box = maaf6_pair_components(w, 3);
    CHECK(box[0].sigma_x == Approx(1e6));
    CHECK(box[1].weight == 0);
    CHECK(box[2].weight == 0);
}

TEST_CASE("MAAF 6D accumulation: one sample's 25 channels by hand, radiance times both subspaces' functions",
          "[maaf6]") {
    const std::vector<Maaf6Component> c = maaf6_pair_components(example_wedge(0.5, 1.0), 3);
    const Maaf6SampleSide side(c);
    REQUIRE(side.channels() == 25);
    std::vector<double> rgb(75, 0.0), weight(25, 0.0);
    const float value[3] = {1, 2, 3};
    const double y1 = 0.1, u1 = 0.02, y2 = -0.2, u2 = 0.05;
    side.accumulate(y1, u1, y2, u2, value, 0.5, rgb.data(), weight.data());
    // Channel (c1, s2) = 1 * 5 + 4: cos(C_y^1 y1 + C_u^1 u1) sin(C_y^2 y2 + C_u^2 u2).
    const double expected = std::cos(4 * y1 + 3.25 * u1) * std::sin(8 * y2 + 5.75 * u2);
    CHECK(weight[9] == Approx(0.5 * expected));
    CHECK(rgb[27] == Approx(1 * expected));
    CHECK(rgb[28] == Approx(2 * expected));
    CHECK(rgb[29] == Approx(3 * expected));
    // Channel (s2, c0) = 4 * 5 + 0 uses subspace 1's coordinates only.
    CHECK(weight[20] == Approx(0.5 * std::sin(8 * y1 + 5.75 * u1)));
    CHECK(weight[0] == 0.5);
    // A swapped subspace would give another value.
    CHECK(std::fabs(rgb[27] - std::cos(4 * y2 + 3.25 * u2) * std::sin(8 * y1 + 5.75 * u1)) > 1e-3);
}

TEST_CASE("MAAF 6D x kernel is MAAF Eq. 13's cos/-sin pair with k-scaled envelopes, the cos part less its DC",
          "[maaf6]") {
    const std::vector<Maaf6Component> c = maaf6_pair_components(example_wedge(0.5, 1.0), 3);
    double kernel[5];
    const double dx = 0.3, k = 3;
    maaf6_x_kernel(c, k, dx, kernel);
    auto g = [&](double sigma) { return std::exp(-0.5 * (dx * sigma / k) * (dx * sigma / k)); };
    CHECK(kernel[0] == Approx(g(c[0].sigma_x)));
    auto dc = [&](const Maaf6Component &p) {
        const double ratio = p.centre_x * k / p.sigma_x;
        return std::exp(-0.5 * ratio * ratio);
    };
    CHECK(kernel[1] == Approx(2 * c[1].weight * (std::cos(c[1].centre_x * dx) - dc(c[1])) * g(c[1].sigma_x)));
    CHECK(kernel[3] == Approx(2 * c[2].weight * (std::cos(c[2].centre_x * dx) - dc(c[2])) * g(c[2].sigma_x)));
    CHECK(kernel[2] == Approx(-2 * c[1].weight * std::sin(c[1].centre_x * dx) * g(c[1].sigma_x)));
    CHECK(kernel[4] == Approx(-2 * c[2].weight * std::sin(c[2].centre_x * dx) * g(c[2].sigma_x)));
}

TEST_CASE("MAAF 6D tangent frame: orthonormal, the light's axis_u on a floor under it", "[maaf6]") {
    Vec3 t1, t2;
    maaf6_tangent_frame({0, 1, 0}, {1, 0, 0}, {0, 0, 1}, t1, t2);
    CHECK(t1.x == Approx(1));
    CHECK(std::fabs(t2.z) == Approx(1));
    maaf6_tangent_frame({1, 0, 0}, {1, 0, 0}, {0, 0, 1}, t1, t2);  // a wall facing along axis_u
    CHECK(std::fabs(dot(t1, Vec3{1, 0, 0})) < 1e-6);
    CHECK(dot(t1, t2) == Approx(0).margin(1e-6));
    CHECK(length(t2) == Approx(1));
}

TEST_CASE(
    "MAAF 6D filter components: the axis-aligned filter where the window or the x band cannot hold the "
    "partition, by hand",
    "[maaf6]") {
    // example_wedge: Omega_y^max / y_min = 10 rad/m, x band min(1e6, 100 / 0.5) = 200: the y band
    // limits the wedge; sigma_x^0 = 10 / 5 = 2 rad/m, so the central reach 3 k / sigma_x^0 is 1.5 m.
    Maaf6Wedge w = example_wedge(0.5, 1.0);
    const std::vector<Maaf6Component> all = maaf6_pair_components(w, 3), one = maaf6_pair_components(w, 1);
    auto same = [](const Maaf6Component &a, const Maaf6Component &b) {
        return a.centre_x == b.centre_x && a.sigma_x == b.sigma_x && a.centre_y == b.centre_y &&
               a.centre_u == b.centre_u && a.weight == b.weight;
    };
    const std::vector<Maaf6Component> wide = maaf6_filter_components(w, 3, 1.0, 1.6);
    for (std::size_t p = 0; p < 3; ++p) CHECK(same(wide[p], all[p]));
    auto check_central_only = [&](const std::vector<Maaf6Component> &c, const Maaf6Component &central) {
        REQUIRE(c.size() == 3);
        CHECK(same(c[0], central));
        CHECK(c[1].weight == 0);
        CHECK(c[2].weight == 0);
    };
    check_central_only(maaf6_filter_components(w, 3, 1.0, 1.4), one[0]);  // the window: 1.5 m > 1.4 m
    check_central_only(maaf6_filter_components(w, 3, 2.0, 1.6), one[0]);  // k = 2: 3 m > 1.6 m
    w.omega_x_max = 5;  // Omega_y^max / y_min = 10 >= the pixel band 5: the band clips the wedge
    check_central_only(maaf6_filter_components(w, 3, 1.0, 1e3), maaf6_pair_components(w, 1)[0]);
    CHECK(maaf6_filter_components(w, 1, 1.0, 1e3).size() == 1);
}

TEST_CASE("MAAF 6D x kernel: each pair's cos part integrates to 0 (nothing passes at Omega_x = 0)",
          "[maaf6]") {
    const std::vector<Maaf6Component> c = maaf6_pair_components(example_wedge(0.5, 1.0), 3);
    for (double k : {1.0, 3.0}) {
        double integral[5] = {0, 0, 0, 0, 0}, first_moment_sin = 0;
        const double step = 1e-3;
        for (double dx = -20; dx <= 20; dx += step) {
            double kernel[5];
            maaf6_x_kernel(c, k, dx, kernel);
            for (int a = 0; a < 5; ++a) integral[a] += kernel[a] * step;
            first_moment_sin += kernel[2] * dx * step;
        }
        INFO("k " << k);
        CHECK(integral[0] == Approx(std::sqrt(2 * 3.14159265358979) * k / c[0].sigma_x).epsilon(1e-6));
        CHECK(std::fabs(integral[1]) < 1e-6 * integral[0]);
        CHECK(std::fabs(integral[3]) < 1e-6 * integral[0]);
        CHECK(std::fabs(integral[2]) < 1e-9);       // odd
        CHECK(std::fabs(first_moment_sin) > 1e-3);  // but not zero
    }
}

TEST_CASE("MAAF 6D filter components: the focal-plane box (u slopes of both signs) keeps the central filter",
          "[maaf6]") {
    // The y-wedge [1, 2] at Omega_y^max 10 is not clipped by the x band (1e6) and sigma_x^0 = 2 rad/m reaches
    // 1.5 m, inside a 1e3 m window: only the u-wedge decides.
    auto same = [](const Maaf6Component &a, const Maaf6Component &b) {
        return a.centre_x == b.centre_x && a.sigma_x == b.sigma_x && a.centre_y == b.centre_y &&
               a.centre_u == b.centre_u && a.weight == b.weight;
    };
    const Maaf6Wedge one_signed = example_wedge(0.01, 0.02);  // near focus, but on one side of it
    const std::vector<Maaf6Component> kept = maaf6_filter_components(one_signed, 3, 1.0, 1e3);
    const std::vector<Maaf6Component> partition = maaf6_pair_components(one_signed, 3);
    for (std::size_t p = 0; p < 3; ++p) CHECK(same(kept[p], partition[p]));
    CHECK(kept[2].weight > 0);
    for (const auto &[u_min, u_max] :
         {std::pair{-0.01, 0.02}, std::pair{-0.5, 1.0}, std::pair{-1.0, 0.001}}) {
        const Maaf6Wedge box = example_wedge(u_min, u_max);
        const std::vector<Maaf6Component> c = maaf6_filter_components(box, 3, 1.0, 1e3);
        REQUIRE(c.size() == 3);
        CHECK(same(c[0], maaf6_pair_components(box, 1)[0]));
        CHECK(c[0].sigma_x == Approx(10.0));  // N = 1: Omega_y^max / y_min, the axis-aligned filter
        CHECK(c[1].weight == 0);
        CHECK(c[2].weight == 0);
    }
}

TEST_CASE("MAAF 6D light attenuation: the Gaussian light model's spectrum at the pair's y centre, by hand",
          "[maaf6]") {
    // Omega_y^max = 2 / sigma with sigma = 0.05 m: exp(-(sigma C_y)^2 / 2).
    CHECK(maaf6_light_attenuation(0.0, 40.0) == 1.0);
    CHECK(maaf6_light_attenuation(20.0, 40.0) == Approx(std::exp(-0.5)));  // sigma C_y = 1
    CHECK(maaf6_light_attenuation(-32.0, 40.0) == Approx(std::exp(-0.5 * 1.6 * 1.6)));
    // N = 3: C_y^2 = 0.8 Omega_y^max, where Eq. 10's own factor is exp(-0.32) = 0.73 and the light's 0.28.
    CHECK(maaf6_light_attenuation(0.8 * 2.8, 2.8) == Approx(std::exp(-1.28)));
    CHECK_THROWS(maaf6_light_attenuation(1.0, 0.0));
}

TEST_CASE("MAAF 6D partition check: each of the filter's reasons for the central filter, by hand",
          "[maaf6]") {
    // example_wedge(0.01, 0.02): x band min(1e6, 100 / 0.01) = 1e4 > Omega_y^max / y_min = 10, so not
    // clipped; sigma_x^0 = 10 / 5 = 2 rad/m reaches 3 k / 2 = 1.5 m.
    Maaf6Wedge w = example_wedge(0.01, 0.02);
    Maaf6PartitionCheck c = maaf6_partition_check(w, 3, 1.0, 1.6);
    CHECK(c.partition_used());
    c = maaf6_partition_check(w, 3, 1.0, 1.4);  // (a): 1.5 m > 1.4 m
    CHECK((c.beyond_window && !c.band_clipped && !c.focal_box));
    w.omega_x_max = 5;  // (b): 10 >= 5; the clipped sigma_x^0 = 5 / 5 = 1 reaches 3 m
    c = maaf6_partition_check(w, 3, 1.0, 3.1);
    CHECK((!c.beyond_window && c.band_clipped && !c.focal_box));
    c = maaf6_partition_check(w, 3, 1.0, 2.9);
    CHECK((c.beyond_window && c.band_clipped && !c.focal_box));
    c = maaf6_partition_check(example_wedge(-0.01, 0.02), 3, 1.0, 1.6);  // (c) alone: the x band stays 1e6
    CHECK((!c.beyond_window && !c.band_clipped && c.focal_box));
    CHECK(maaf6_partition_check(example_wedge(-0.01, 0.02), 1, 1.0, 1e-3)
              .partition_used());  // N = 1: nothing to drop
    // Whatever the check says, maaf6_filter_components() keeps the offset pairs exactly where it passes.
    for (double window_m : {1.4, 1.6, 2.9, 3.1})
        for (double omega_x : {5.0, 1e6})
            for (double u_min : {-0.01, 0.01}) {
                Maaf6Wedge v = example_wedge(u_min, 0.02);
                v.omega_x_max = omega_x;
                const bool kept = maaf6_filter_components(v, 3, 1.0, window_m)[2].weight > 0;
                CHECK(kept == maaf6_partition_check(v, 3, 1.0, window_m).partition_used());
            }
}

TEST_CASE("MAAF 6D lens band: the x band of the lens wedge alone, 0 where there is none to filter, by hand",
          "[maaf6]") {
    Maaf6Wedge w = example_wedge(0.2, 0.4);
    w.omega_u_max = 10;
    w.omega_x_max = 100;
    CHECK(maaf6_lens_band(w) == Approx(50));  // Omega_u^max / min |s_u| = 10 / 0.2
    w.u_min = -0.4;
    w.u_max = -0.25;
    CHECK(maaf6_lens_band(w) == Approx(40));  // behind the focal plane: |s_u|
    w.omega_x_max = 40;
    CHECK(maaf6_lens_band(w) == 0);  // clipped by the pixel band: the pixel's own mean
    w.omega_x_max = 100;
    w.u_max = 0.1;
    CHECK(maaf6_lens_band(w) == 0);  // the focal-plane box
    w.has_u = false;
    CHECK(maaf6_lens_band(w) == 0);  // pinhole
}
