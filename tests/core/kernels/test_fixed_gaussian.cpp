#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>
#include <vector>

#include "aaf/core/kernels/fixed_gaussian.h"
#include "aaf/core/util/error.h"

using namespace aaf;

TEST_CASE("Fixed Gaussian keeps a constant image and conserves an impulse", "[baseline]") {
    const int w = 21, h = 21;
    std::vector<float> constant(w * h, 0.375f), out(w * h);
    fixed_gaussian_filter(plane_view(constant.data(), w, h), 2.5f, plane_view(out.data(), w, h));
    for (float v : out) CHECK(v == Approx(0.375f).epsilon(1e-6));

    // An impulse far from the borders spreads into weights that sum to one,
    // symmetric about the centre, with the 1D Gaussian ratio between neighbours.
    std::vector<float> impulse(w * h, 0.0f);
    impulse[10 * w + 10] = 1.0f;
    fixed_gaussian_filter(plane_view(impulse.data(), w, h), 1.5f, plane_view(out.data(), w, h));
    CHECK(std::accumulate(out.begin(), out.end(), 0.0) == Approx(1.0).epsilon(1e-5));
    CHECK(out[10 * w + 9] == Approx(out[10 * w + 11]));
    CHECK(out[9 * w + 10] == Approx(out[11 * w + 10]));
    CHECK(out[10 * w + 11] / out[10 * w + 10] == Approx(std::exp(-0.5 / (1.5 * 1.5))));

    fixed_gaussian_filter(plane_view(impulse.data(), w, h), 0.0f, plane_view(out.data(), w, h));
    CHECK(out == impulse);
    CHECK_THROWS_AS(
        fixed_gaussian_filter(plane_view(impulse.data(), w, h), -1.0f, plane_view(out.data(), w, h)), Error);
}
