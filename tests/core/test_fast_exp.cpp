#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "aaf/core/fast_exp.h"

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
