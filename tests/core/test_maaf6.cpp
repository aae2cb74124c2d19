// MAAF for combined effects (Wu et al. 2017, Sec. 6.2): the 3D partition,
// the 6D accumulation layout and the filter's normalisation, against values
// computed by hand.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "aaf/core/maaf6.h"
#include "aaf/core/maaf6_filter.h"
#include "aaf/core/maaf_components.h"

using namespace aaf;

namespace {

/// y-wedge [1, 2] with Omega_y^max 10 and a u-wedge of slopes [u_min, u_max] (Omega_u^max 100).
Maaf6Wedge example_wedge(double u_min, double u_max) {
    Maaf6Wedge w;
    w.has_y = true;
    w.y_min = 1;
    w.y_max = 2;
    w.omega_y_max = 10;
    w.has_u = true;
    w.u_min = u_min;
    w.u_max = u_max;
    w.omega_u_max = 100;
    w.omega_x_max = 1e6;
    return w;
}

/// The planes maaf6_filter_layer() reads, all width x height, and the views of them it takes.
struct Maaf6Planes {
    int width = 0, height = 0;
    std::vector<std::vector<float>> sums, weights;  ///< 3 (2N-1)^2 and (2N-1)^2 of them
    std::vector<float> y_min, y_max, u_min, u_max, omega_x, id, pixel_size, spp, position[3], normal[3];

    Maaf6LayerInputs layer(double omega_y_max) const {
        Maaf6LayerInputs in;
        for (const auto &p : sums) in.sums.push_back(view(p));
        for (const auto &p : weights) in.weights.push_back(view(p));
        in.y_min = view(y_min);
        in.y_max = view(y_max);
        in.omega_y_max = omega_y_max;
        return in;
    }
    Maaf6SharedInputs shared(double omega_u_max) const {
        Maaf6SharedInputs in;
        in.u_min = view(u_min);
        in.u_max = view(u_max);
        in.omega_x = view(omega_x);
        for (std::size_t c = 0; c < 3; ++c) {
            in.position[c] = view(position[c]);
            in.normal[c] = view(normal[c]);
        }
        in.object_id = view(id);
        in.pixel_size = view(pixel_size);
        in.samples = view(spp);
        in.omega_u_max = omega_u_max;
        return in;
    }

  private:
    ConstPlaneView view(const std::vector<float> &plane) const {
        return plane_view<const float>(plane.data(), width, height);
    }
};

}  // namespace

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

TEST_CASE("MAAF 6D filter: a fully lit region keeps each pixel's own mean exactly, whatever the wedges",
          "[maaf6]") {
    // Each sample's radiance is c times its unoccluded weight (nothing occluded): the filtered ratio is c
    // and the output c times the pixel's own mean weight, i.e. its own mean (AAF's r(x) V(x) with V = 1);
    // with unit weights that is a constant image.
    const int width = 24, height = 16, n = width * height;
    Maaf6Planes planes;
    planes.width = width;
    planes.height = height;
    auto &sums = planes.sums, &weights = planes.weights;
    auto &ymin = planes.y_min, &ymax = planes.y_max, &umin = planes.u_min, &umax = planes.u_max;
    auto &pos = planes.position, &nrm = planes.normal;
    sums.assign(75, std::vector<float>(n));
    weights.assign(25, std::vector<float>(n));
    for (auto *p : {&ymin, &ymax, &umin, &umax}) p->assign(n, 0.0f);
    planes.omega_x.assign(n, 200.0f);
    planes.id.assign(n, 1.0f);
    planes.pixel_size.assign(n, 0.01f);
    planes.spp.assign(n, 16.0f);
    std::vector<float> own[3];
    for (auto &o : own) o.assign(n, 0.0f);
    for (int c = 0; c < 3; ++c) {
        pos[c].assign(n, 0.0f);
        nrm[c].assign(n, c == 1 ? 1.0f : 0.0f);
    }
    const bool unit_weights = GENERATE(true, false);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    const float value[3] = {0.25f, 0.5f, 0.75f};
    for (int i = 0; i < n; ++i) {
        pos[0][std::size_t(i)] = 0.01f * float(i % width);
        pos[2][std::size_t(i)] = 0.01f * float(i / width);
        Maaf6Wedge w = example_wedge(-0.2 + 0.6 * unit(rng), 0.5 + unit(rng));
        w.y_min = 0.5 + unit(rng);
        w.y_max = w.y_min + unit(rng);
        w.omega_x_max = 200;
        ymin[std::size_t(i)] = float(w.y_min);
        ymax[std::size_t(i)] = float(w.y_max);
        umin[std::size_t(i)] = float(w.u_min);
        umax[std::size_t(i)] = float(w.u_max);
        w.y_min = double(ymin[std::size_t(i)]);
        const Maaf6SampleSide side(maaf6_pair_components(w, 3));
        std::vector<double> rgb(75, 0.0), weight(25, 0.0);
        for (int s = 0; s < 16; ++s) {
            const double w_s = unit_weights ? 1.0 : 0.2 + unit(rng);
            const float lit[3] = {float(value[0] * w_s), float(value[1] * w_s), float(value[2] * w_s)};
            side.accumulate(unit(rng) - 0.5, 0.1 * unit(rng), unit(rng) - 0.5, 0.1 * unit(rng), lit, w_s, rgb.data(),
                            weight.data());
        }
        for (int c = 0; c < 3; ++c) own[c][std::size_t(i)] = float(rgb[std::size_t(c)] / 16.0);
        for (int c = 0; c < 75; ++c) sums[std::size_t(c)][std::size_t(i)] = float(rgb[std::size_t(c)]);
        for (int c = 0; c < 25; ++c) weights[std::size_t(c)][std::size_t(i)] = float(weight[std::size_t(c)]);
    }
    const Maaf6LayerInputs layer = planes.layer(10);
    const Maaf6SharedInputs shared = planes.shared(100);
    LightPlane light;
    light.axis_u = {1, 0, 0};
    light.axis_v = {0, 0, 1};
    std::vector<float> out[3];
    for (auto &o : out) o.assign(n, -1.0f);
    const std::array<PlaneView, 3> views = {plane_view(out[0].data(), width, height),
                                            plane_view(out[1].data(), width, height),
                                            plane_view(out[2].data(), width, height)};
    for (int pairs : {3, 1}) {
        Maaf6FilterParams params;
        params.pairs_used = pairs;
        maaf6_filter_layer(layer, shared, light, params, views);
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < n; ++i) {
                REQUIRE(out[c][std::size_t(i)] == Approx(own[c][std::size_t(i)]).epsilon(1e-4));
                if (unit_weights) REQUIRE(out[c][std::size_t(i)] == Approx(value[c]).epsilon(1e-4));
            }
    }
}

namespace {

/// A flat floor of pixels of 1 cm whose radiance is a soft edge
/// g(x_a + s v) along the tangent axis t_a of one subspace a (1 or 2), v the
/// sample's coordinate in that subspace (y_a for a y-wedge, u_a for a
/// u-wedge), drawn at the midpoints of 256 strata of [-half, half];
/// accumulated through Maaf6SampleSide (as the tracer does) and filtered by
/// maaf6_filter_layer(). Returns the largest |filtered - exact integral over v|
/// over the pixels whose window lies inside the image.
struct EdgeCase {
    bool y_wedge = true;         ///< the slope on y (has_y) or on u (no y-wedge, lens only)
    double slope = 1;            ///< s of the signal
    double wedge_lo = 1, wedge_hi = 1;  ///< the stored wedge (y or u slopes)
    double half = 0.05;          ///< v uniform on [-half, half]
    double omega_v = 40;         ///< Omega^max of v
    double edge_m = 0.02;        ///< the edge's own width
    int axis = 1;                ///< the subspace a
    double k = 1;                ///< Maaf6FilterParams::k
    bool light_weights = false;  ///< Maaf6FilterParams::light_weights
};

double edge_error(const EdgeCase &e, int pairs_used) {
    // 41 pixels along the edge's axis, 25 (one window) across it.
    const int width = e.axis == 1 ? 41 : 25, height = e.axis == 1 ? 25 : 41, n = width * height, strata = 256;
    const double pixel_m = 0.01;
    auto g = [&](double t) { return 0.5 + 0.5 * std::tanh((t - 0.2) / e.edge_m); };
    Maaf6Planes planes;
    planes.width = width;
    planes.height = height;
    auto &sums = planes.sums, &weights = planes.weights;
    auto &pos = planes.position, &nrm = planes.normal;
    sums.assign(75, std::vector<float>(n));
    weights.assign(25, std::vector<float>(n));
    planes.y_min.assign(n, e.y_wedge ? float(e.wedge_lo) : -1.0f);
    planes.y_max.assign(n, e.y_wedge ? float(e.wedge_hi) : -1.0f);
    planes.u_min.assign(n, e.y_wedge ? 0.0f : float(e.wedge_lo));
    planes.u_max.assign(n, e.y_wedge ? 0.0f : float(e.wedge_hi));
    planes.omega_x.assign(n, float(2 / pixel_m));
    planes.id.assign(n, 1.0f);
    planes.pixel_size.assign(n, float(pixel_m));
    planes.spp.assign(n, float(strata));
    std::vector<float> exact(n);
    for (int c = 0; c < 3; ++c) {
        pos[c].assign(n, 0.0f);
        nrm[c].assign(n, c == 1 ? 1.0f : 0.0f);
    }
    Maaf6Wedge w;
    w.has_y = e.y_wedge;
    w.y_min = e.y_wedge ? e.wedge_lo : 0;
    w.y_max = e.y_wedge ? e.wedge_hi : 0;
    w.omega_y_max = e.omega_v;
    w.has_u = !e.y_wedge;
    w.u_min = e.y_wedge ? 0 : e.wedge_lo;
    w.u_max = e.y_wedge ? 0 : e.wedge_hi;
    w.omega_u_max = e.omega_v;
    w.omega_x_max = 2 / pixel_m;
    const Maaf6SampleSide side(maaf6_pair_components(w, 3));
    for (int i = 0; i < n; ++i) {
        // On this floor (normal +y) t1 = the light's axis_u = +x and t2 = n x t1 = -z.
        pos[0][std::size_t(i)] = float(pixel_m * (i % width));
        pos[2][std::size_t(i)] = float(pixel_m * (i / width));
        const double x_a = e.axis == 1 ? double(pos[0][std::size_t(i)]) : -double(pos[2][std::size_t(i)]) + 0.4;
        std::vector<double> rgb(75, 0.0), weight(25, 0.0);
        double mean = 0;
        for (int k = 0; k < strata; ++k) {
            const double v = e.half * (2.0 * (k + 0.5) / strata - 1.0);
            const double f = g(x_a + e.slope * v);
            mean += f / strata;
            const float value[3] = {float(f), float(f), float(f)};
            const double y = e.y_wedge ? v : 0.0, u = e.y_wedge ? 0.0 : v;
            side.accumulate(e.axis == 1 ? y : 0.0, e.axis == 1 ? u : 0.0, e.axis == 2 ? y : 0.0, e.axis == 2 ? u : 0.0,
                            value, 1.0, rgb.data(), weight.data());
        }
        exact[std::size_t(i)] = float(mean);
        for (int c = 0; c < 75; ++c) sums[std::size_t(c)][std::size_t(i)] = float(rgb[std::size_t(c)]);
        for (int c = 0; c < 25; ++c) weights[std::size_t(c)][std::size_t(i)] = float(weight[std::size_t(c)]);
    }
    const Maaf6LayerInputs layer = planes.layer(e.omega_v);
    const Maaf6SharedInputs shared = planes.shared(e.y_wedge ? 0.0 : e.omega_v);
    LightPlane light;
    light.axis_u = {1, 0, 0};
    light.axis_v = {0, 0, 1};
    std::vector<float> out[3];
    for (auto &o : out) o.assign(n, -1.0f);
    const std::array<PlaneView, 3> views = {plane_view(out[0].data(), width, height),
                                            plane_view(out[1].data(), width, height),
                                            plane_view(out[2].data(), width, height)};
    Maaf6FilterParams params;
    params.pairs_used = pairs_used;
    params.k = e.k;
    params.light_weights = e.light_weights;
    maaf6_filter_layer(layer, shared, light, params, views);
    double worst = 0;
    for (int y = params.max_radius_px; y < height - params.max_radius_px; ++y)
        for (int x = params.max_radius_px; x < width - params.max_radius_px; ++x) {
            const std::size_t i = std::size_t(y * width + x);
            worst = std::max(worst, std::fabs(double(out[0][i]) - double(exact[i])));
        }
    return worst;
}

}  // namespace

TEST_CASE("MAAF 6D synthetic edge: no bias from pairs the window cannot resolve, in either subspace", "[maaf6]") {
    // Indirect light's numbers (s = z = 2 m, Omega_y^max = 2.8 per unit tan): the Omega_x extent is
    // 1.4 rad/m, the central component's 3 std 11 m against a 12 cm window. Inside it cos(C_x dx) ~ 1,
    // so the pairs would weight each pixel's samples by 1 + 2 mu_p cos(C_y^p y): 7e-3 off before.
    // The edge is linear over the window, so the axis-aligned filter is exact there.
    for (int axis : {1, 2}) {
        EdgeCase e;
        e.axis = axis;
        e.slope = e.wedge_lo = 2.0;
        e.wedge_hi = 2.5;
        e.half = 1.0;
        e.omega_v = 2.8;
        e.edge_m = 0.3;
        const double aaf = edge_error(e, 1), maaf = edge_error(e, 3);
        INFO("axis " << axis << ": AAF " << aaf << ", MAAF " << maaf);
        CHECK(aaf < 1e-4);
        CHECK(maaf < 1e-4);
    }
}

TEST_CASE("MAAF 6D synthetic edge: a lens-only pixel whose u-wedge the pixel band clips keeps its own mean",
          "[maaf6]") {
    // Nearly in focus (s_u = 0.1, a circle of confusion of 0.5 cm against 1 cm pixels): Omega_u^max / s_u
    // = 400 rad/m is past the pixel band 200, so the filter's band would be the pixel band itself, and a
    // sharp edge (1 cm) only gets blurred. Each pixel keeps its own mean, which with 256 strata is the
    // exact integral; a u-wedge inside the band is still filtered (the sign test below).
    for (int axis : {1, 2}) {
        EdgeCase e;
        e.axis = axis;
        e.y_wedge = false;
        e.slope = e.wedge_lo = e.wedge_hi = 0.1;
        e.omega_v = 40;
        e.edge_m = 0.01;
        const double aaf = edge_error(e, 1), maaf = edge_error(e, 3);
        INFO("axis " << axis << ": AAF " << aaf << ", MAAF " << maaf);
        CHECK(aaf < 1e-5);
        CHECK(maaf < 1e-5);
        // One notch inside the band (Omega_u^max / s_u = 190 < 200): filtered, so the sharp edge moves.
        e.omega_v = 19;
        CHECK(edge_error(e, 1) > 1e-3);
    }
}

TEST_CASE("MAAF 6D synthetic edge: the tap - centre displacement matches the wedge's sign, per subspace",
          "[maaf6]") {
    // g(x_a + s v) has its spectrum on Omega_v = s Omega_x; the partition is active (Omega_x extent
    // 160-178 rad/m < the pixel band 200, central 3 std 8-9 cm < the 12 cm window). The filter is
    // closer to the exact integral when the stored wedge has the signal's sign than the opposite one.
    for (int axis : {1, 2}) {
        {  // y (light), s > 0: the signal mirrored in y is the wrong orientation
            EdgeCase e;
            e.axis = axis;
            e.slope = 0.3;
            e.wedge_lo = 0.25;
            e.wedge_hi = 0.35;
            const double right = edge_error(e, 3);
            e.slope = -0.3;
            const double wrong = edge_error(e, 3);
            INFO("axis " << axis << ": right " << right << ", mirrored " << wrong);
            CHECK(right < wrong);
        }
        for (double sign : {1.0, -1.0}) {
            EdgeCase e;
            e.axis = axis;
            e.y_wedge = false;
            e.slope = 0.5 * sign;
            e.wedge_lo = sign > 0 ? 0.45 : -0.55;
            e.wedge_hi = sign > 0 ? 0.55 : -0.45;
            e.omega_v = 80;
            const double right = edge_error(e, 3);
            e.slope = -e.slope;
            const double wrong = edge_error(e, 3);
            INFO("axis " << axis << ", u, sign " << sign << ": right " << right << ", opposite " << wrong);
            CHECK(right < wrong);
        }
    }
}

TEST_CASE("MAAF 6D filter components: the axis-aligned filter where the window or the x band cannot hold the "
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

TEST_CASE("MAAF 6D x kernel: each pair's cos part integrates to 0 (nothing passes at Omega_x = 0)", "[maaf6]") {
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
        CHECK(std::fabs(integral[2]) < 1e-9);  // odd
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
    for (const auto &[u_min, u_max] : {std::pair{-0.01, 0.02}, std::pair{-0.5, 1.0}, std::pair{-1.0, 0.001}}) {
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

TEST_CASE("MAAF 6D synthetic soft edge at k = 0.5: the light-attenuated pair weights over-sharpen less than "
          "Eq. 10's",
          "[maaf6]") {
    // A y-wedge the partition covers (as in the orientation test above), v uniform on [-5, 5] cm
    // with Omega_y^max = 2 / 5 cm: the light of the toolkit's sigma = half its side. At k = 0.5 (wider
    // Fourier Gaussians, which overlap along the wedge) Eq. 10's weights over-sharpen: 0.020 against
    // 0.017 light-attenuated. At k = 1 the attenuation is too strong on this edge (0.044 against 0.017),
    // which is why it is an option and not the default.
    EdgeCase e;
    e.slope = 0.3;
    e.wedge_lo = 0.25;
    e.wedge_hi = 0.35;
    e.k = 0.5;
    const double eq10 = edge_error(e, 3);
    e.light_weights = true;
    const double light = edge_error(e, 3);
    INFO("Eq. 10 " << eq10 << ", light-attenuated " << light);
    CHECK(light < eq10);
}

TEST_CASE("MAAF 6D partition check: each of the filter's reasons for the central filter, by hand", "[maaf6]") {
    // example_wedge(0.01, 0.02): x band min(1e6, 100 / 0.01) = 1e4 > Omega_y^max / y_min = 10, so not clipped;
    // sigma_x^0 = 10 / 5 = 2 rad/m reaches 3 k / 2 = 1.5 m.
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
    CHECK(maaf6_partition_check(example_wedge(-0.01, 0.02), 1, 1.0, 1e-3).partition_used());  // N = 1: nothing to drop
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

TEST_CASE("MAAF 6D partition census: the filter's choice per pixel, with its window of max radius times the "
          "pixel size",
          "[maaf6]") {
    // Seven pixels in a row: background; a hit without a wedge (no y-wedge, u slopes of both signs);
    // the partition; (a); (b); (a) and (b); (c) (a y-wedge, u slopes of both signs). example_wedge's y-wedge [1, 2] at Omega_y^max 10
    // (central reach 1.5 m unclipped, 3 m clipped to the x band 5); windows 12 px times the pixel size.
    const int width = 7, height = 1, n = width * height;
    Maaf6Planes planes;
    planes.width = width;
    planes.height = height;
    planes.sums.assign(75, std::vector<float>(n, 0.0f));
    planes.weights.assign(25, std::vector<float>(n, 0.0f));
    planes.id = {0, 1, 1, 1, 1, 1, 1};
    planes.y_min = {-1, -1, 1, 1, 1, 1, 1};
    planes.y_max = {-1, -1, 2, 2, 2, 2, 2};
    planes.u_min = {0.01f, -0.01f, 0.01f, 0.01f, 0.01f, 0.01f, -0.01f};
    planes.u_max.assign(n, 0.02f);
    planes.omega_x = {1e6f, 1e6f, 1e6f, 1e6f, 5, 5, 1e6f};
    planes.pixel_size = {1, 1, 1, 0.1f, 1, 0.2f, 1};
    planes.spp.assign(n, 16.0f);
    for (int c = 0; c < 3; ++c) {
        planes.position[c].assign(n, 0.0f);
        planes.normal[c].assign(n, c == 1 ? 1.0f : 0.0f);
    }
    const Maaf6LayerInputs layer = planes.layer(10);
    const Maaf6SharedInputs shared = planes.shared(100);
    Maaf6FilterParams params;  // k 1, max radius 12 px, N = 3
    Maaf6PartitionCensus census = maaf6_partition_census(layer, shared, params);
    CHECK(census.background == 1);
    CHECK(census.no_wedge == 1);
    CHECK(census.filtered == 5);
    CHECK(census.by_reasons == std::array<long, 8>{1, 1, 1, 1, 1, 0, 0, 0});
    params.max_radius_px = 40;  // windows 4 m and 8 m: no pixel reaches beyond
    census = maaf6_partition_census(layer, shared, params);
    CHECK(census.by_reasons == std::array<long, 8>{2, 0, 2, 0, 1, 0, 0, 0});
    params.pairs_used = 1;
    census = maaf6_partition_census(layer, shared, params);
    CHECK(census.by_reasons == std::array<long, 8>{5, 0, 0, 0, 0, 0, 0, 0});
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

TEST_CASE("MAAF 6D filter: with a lens wedge the unoccluded light is filtered with the lens band, not kept per "
          "pixel",
          "[maaf6]") {
    // Defocus spreads a pixel's samples over whatever surfaces the lens rays hit, so the unoccluded light of
    // its samples differs from pixel to pixel: here a checkerboard of 0.5 and 1.5 (mean 1), every other
    // sample occluded (ratio 0.5). Taking the pixel's own mean of it (AAF's r(x) V(x) factoring) would keep
    // the checkerboard; filtered with the lens band (std k / 20 rad/m = 5 px) it averages out. Nearly in
    // focus (the band clipped by the pixel band) each pixel keeps its own.
    const int width = 41, height = 41, n = width * height;
    const double pixel_m = 0.01;
    for (const double s_u : {0.5, 0.02}) {
        Maaf6Planes planes;
        planes.width = width;
        planes.height = height;
        planes.sums.assign(75, std::vector<float>(n));
        planes.weights.assign(25, std::vector<float>(n));
        planes.y_min.assign(n, -1.0f);
        planes.y_max.assign(n, -1.0f);
        planes.u_min.assign(n, float(s_u));
        planes.u_max.assign(n, float(s_u));
        planes.omega_x.assign(n, float(2 / pixel_m));
        planes.id.assign(n, 1.0f);
        planes.pixel_size.assign(n, float(pixel_m));
        planes.spp.assign(n, 16.0f);
        for (int c = 0; c < 3; ++c) {
            planes.position[c].assign(n, 0.0f);
            planes.normal[c].assign(n, c == 1 ? 1.0f : 0.0f);
        }
        Maaf6Wedge w;
        w.has_y = false;
        w.has_u = true;
        w.u_min = w.u_max = s_u;
        w.omega_u_max = 10;
        w.omega_x_max = 2 / pixel_m;
        const Maaf6SampleSide side(maaf6_pair_components(w, 3));
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> lens(-0.1, 0.1);
        const float colour[3] = {0.2f, 0.4f, 0.8f};
        std::vector<float> own_unoccluded(n);
        for (int i = 0; i < n; ++i) {
            const int x = i % width, y = i / width;
            planes.position[0][std::size_t(i)] = float(pixel_m * x);
            planes.position[2][std::size_t(i)] = float(pixel_m * y);
            const double unoccluded = (x + y) % 2 ? 1.5 : 0.5;
            own_unoccluded[std::size_t(i)] = float(unoccluded);
            std::vector<double> rgb(75, 0.0), weight(25, 0.0);
            for (int s = 0; s < 16; ++s) {
                const float visible = s % 2 ? 1.0f : 0.0f;
                const float value[3] = {float(colour[0] * unoccluded) * visible, float(colour[1] * unoccluded) * visible,
                                        float(colour[2] * unoccluded) * visible};
                side.accumulate(0, lens(rng), 0, lens(rng), value, unoccluded, rgb.data(), weight.data());
            }
            for (int c = 0; c < 75; ++c) planes.sums[std::size_t(c)][std::size_t(i)] = float(rgb[std::size_t(c)]);
            for (int c = 0; c < 25; ++c) planes.weights[std::size_t(c)][std::size_t(i)] = float(weight[std::size_t(c)]);
        }
        LightPlane light;
        light.axis_u = {1, 0, 0};
        light.axis_v = {0, 0, 1};
        std::vector<float> out[3];
        for (auto &o : out) o.assign(n, -1.0f);
        const std::array<PlaneView, 3> views = {plane_view(out[0].data(), width, height),
                                                plane_view(out[1].data(), width, height),
                                                plane_view(out[2].data(), width, height)};
        for (int pairs : {3, 1}) {
            INFO("s_u " << s_u << ", pairs " << pairs);
            Maaf6FilterParams params;
            params.pairs_used = pairs;
            maaf6_filter_layer(planes.layer(10), planes.shared(10), light, params, views);
            for (int y = params.max_radius_px; y < height - params.max_radius_px; ++y)
                for (int x = params.max_radius_px; x < width - params.max_radius_px; ++x) {
                    const std::size_t i = std::size_t(y * width + x);
                    const double unoccluded = s_u > 0.1 ? 1.0 : double(own_unoccluded[i]);
                    for (int c = 0; c < 3; ++c)
                        REQUIRE(out[c][i] == Approx(0.5 * colour[c] * unoccluded).epsilon(0.01));
                }
        }
    }
}

TEST_CASE("MAAF 6D filter: where the guides or the border cut the window, the pixel gets the axis-aligned "
          "filter's own bits; over a whole window the partition",
          "[maaf6]") {
    // A floor (normal +y, 30 columns of 1 cm) meets a wall (normal +x) that its taps reject; noisy
    // visibility on a y-wedge whose partition is active (s 0.25-0.35, Omega_y^max 40, central 3 std
    // 8-9 cm inside the 12 cm window). The pairs' cos and sin kernels cancel only over a whole window.
    const int width = 41, height = 25, n = width * height, wall = 30;
    const double pixel_m = 0.01;
    Maaf6Planes planes;
    planes.width = width;
    planes.height = height;
    planes.sums.assign(75, std::vector<float>(n));
    planes.weights.assign(25, std::vector<float>(n));
    planes.y_min.assign(n, 0.25f);
    planes.y_max.assign(n, 0.35f);
    planes.u_min.assign(n, 0.0f);
    planes.u_max.assign(n, 0.0f);
    planes.omega_x.assign(n, float(2 / pixel_m));
    planes.id.assign(n, 1.0f);
    planes.pixel_size.assign(n, float(pixel_m));
    planes.spp.assign(n, 16.0f);
    for (int c = 0; c < 3; ++c) {
        planes.position[c].assign(n, 0.0f);
        planes.normal[c].assign(n, 0.0f);
    }
    Maaf6Wedge w;
    w.has_y = true;
    w.y_min = 0.25;
    w.y_max = 0.35;
    w.omega_y_max = 40;
    w.has_u = false;
    w.omega_x_max = 2 / pixel_m;
    const Maaf6SampleSide side(maaf6_pair_components(w, 3));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int i = 0; i < n; ++i) {
        const int x = i % width, y = i / width;
        planes.position[0][std::size_t(i)] = float(pixel_m * x);
        planes.position[2][std::size_t(i)] = float(pixel_m * y);
        planes.normal[x < wall ? 1 : 0][std::size_t(i)] = 1.0f;
        std::vector<double> rgb(75, 0.0), weight(25, 0.0);
        for (int s = 0; s < 16; ++s) {
            const float v = unit(rng) < 0.5 ? 1.0f : 0.0f;
            const float value[3] = {v, v, v};
            side.accumulate(0.1 * (unit(rng) - 0.5), 0, 0.1 * (unit(rng) - 0.5), 0, value, 1.0, rgb.data(),
                            weight.data());
        }
        for (int c = 0; c < 75; ++c) planes.sums[std::size_t(c)][std::size_t(i)] = float(rgb[std::size_t(c)]);
        for (int c = 0; c < 25; ++c) planes.weights[std::size_t(c)][std::size_t(i)] = float(weight[std::size_t(c)]);
    }
    LightPlane light;
    light.axis_u = {1, 0, 0};
    light.axis_v = {0, 0, 1};
    std::vector<float> out[2];
    for (int pairs : {3, 1}) {
        std::vector<float> &o = out[pairs == 3 ? 0 : 1];
        std::vector<float> g(n), b(n);
        o.assign(n, -1.0f);
        Maaf6FilterParams params;
        params.pairs_used = pairs;
        maaf6_filter_layer(planes.layer(40), planes.shared(0), light, params,
                           {plane_view(o.data(), width, height), plane_view(g.data(), width, height),
                            plane_view(b.data(), width, height)});
    }
    const int row = height / 2;
    for (int x : {0, 1, wall - 2, wall - 1}) {  // the border or the wall cuts about half the window
        INFO("cut window, column " << x);
        CHECK(out[0][std::size_t(row * width + x)] == out[1][std::size_t(row * width + x)]);
    }
    int differ = 0;
    for (int x = 10; x <= 18; ++x)  // whole windows: the partition
        differ += out[0][std::size_t(row * width + x)] != out[1][std::size_t(row * width + x)];
    CHECK(differ == 9);
    // The census counts the cut windows where the filter gave the axis-aligned bits.
    Maaf6FilterParams params;
    const Maaf6PartitionCensus census = maaf6_partition_census(planes.layer(40), planes.shared(0), params);
    long same = 0;
    for (int i = 0; i < n; ++i) same += out[0][std::size_t(i)] == out[1][std::size_t(i)];
    CHECK(census.by_reasons[0] == n);
    CHECK(census.window_cut == same);
    CHECK(census.window_cut > 2 * height);  // the border columns and the wall's neighbours at least
}
