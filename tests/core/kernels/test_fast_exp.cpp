#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "aaf/core/kernels/fast_exp.h"

TEST_CASE("fast_exp_nonpositive matches std::exp to float accuracy on [-87, 0]", "[math]") {
    double worst = 0;
    for (int i = 0; i <= 200000; ++i) {
        const float x = -87.0f * float(i) / 200000.0f;
        const double exact = std::exp(double(x));
        worst = std::max(worst, std::abs(double(aaf::fast_exp_nonpositive(x)) - exact) / exact);
    }
    CHECK(worst < 3e-7);
    CHECK(aaf::fast_exp_nonpositive(0.0f) == 1.0f);
    CHECK(aaf::fast_exp_nonpositive(-1000.0f) >= 0.0f);
    CHECK(aaf::fast_exp_nonpositive(-1000.0f) < 1e-37f);
}

TEST_CASE("fast_exp_nonpositive gives a weight in [0, 1] for NaN and infinite inputs", "[math]") {
    for (const float x : {std::nanf(""), -std::numeric_limits<float>::infinity(), -3.4e38f, -1e30f}) {
        CAPTURE(x);
        const float y = aaf::fast_exp_nonpositive(x);
        CHECK(y >= 0.0f);
        CHECK(y < 1e-37f);
    }
    CHECK(aaf::fast_exp_nonpositive(std::numeric_limits<float>::infinity()) == 1.0f);
}

namespace {

/// gather_exp_nonpositive<Fused>'s worst relative error against std::exp on
/// [-87, 0]: a fine grid near 0, where the filters' weights live, and the rest.
template <bool Fused>
double gather_exp_worst_error() {
    double worst = 0;
    for (int i = 0; i <= 400000; ++i) {
        const float x = i <= 200000 ? -2.0f * float(i) / 200000.0f : -87.0f * float(i - 200000) / 200000.0f;
        const double exact = std::exp(double(x));
        worst = std::max(worst, std::abs(double(aaf::gather_exp_nonpositive<Fused>(x)) - exact) / exact);
    }
    return worst;
}

}  // namespace

TEST_CASE("gather_exp_nonpositive matches std::exp to float accuracy, fused or not", "[math]") {
    // The degree-5 polynomial's own error is 2.2e-7 (float arithmetic included).
    CHECK(gather_exp_worst_error<true>() < 3e-7);
    CHECK(gather_exp_worst_error<false>() < 3e-7);
    // The centre's own weight is exactly 1, and k = round(x log2 e) lands on
    // whole powers of two: exp(-k ln 2) to within the polynomial's error.
    for (const float zero : {0.0f, -0.0f}) {
        CHECK(aaf::gather_exp_nonpositive<true>(zero) == 1.0f);
        CHECK(aaf::gather_exp_nonpositive<false>(zero) == 1.0f);
    }
    CHECK(aaf::gather_exp_nonpositive<true>(-10.0f * 0.6931471805599453f) ==
          Approx(1.0 / 1024.0).epsilon(3e-7));
}

TEST_CASE("gather_exp_nonpositive gives a weight in [0, 1] for NaN and infinite inputs", "[math]") {
    for (const float x : {std::nanf(""), -std::numeric_limits<float>::infinity(), -3.4e38f, -1e30f, -87.5f}) {
        CAPTURE(x);
        for (const float y : {aaf::gather_exp_nonpositive<true>(x), aaf::gather_exp_nonpositive<false>(x)}) {
            CHECK(y > 0.0f);  // clamped at -87: a normal float, never 0 or a denormal
            CHECK(y < 1e-37f);
        }
    }
    CHECK(aaf::gather_exp_nonpositive<true>(std::numeric_limits<float>::infinity()) == 1.0f);
    CHECK(aaf::gather_exp_nonpositive<false>(1.0f) == 1.0f);
}
