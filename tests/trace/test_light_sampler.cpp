#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "light_sampler.h"
#include "random.h"

using namespace aaf;
using namespace aaf::trace;

TEST_CASE("Truncated normal sampler has the analytic moments", "[trace][light]") {
    // A standard normal truncated to [-1, 1] has mean 0 and variance
    // 1 - 2 phi(1) / (Phi(1) - Phi(-1)) = 1 - 2 * 0.2419707 / 0.6826895 = 0.2911.
    const TruncatedNormal normal(1.0);
    const int n = 200000;
    double sum = 0, sum_sq = 0;
    for (int i = 0; i < n; ++i) {
        const float x = normal.sample((i + 0.5f) / n);  // a uniform grid integrates exactly
        REQUIRE(std::fabs(x) <= 1.0f);
        sum += x;
        sum_sq += double(x) * x;
    }
    CHECK(sum / n == Approx(0.0).margin(1e-6));
    CHECK(sum_sq / n == Approx(0.29112).epsilon(1e-3));
    CHECK(normal.sample(0.0f) == -1.0f);
    CHECK(normal.sample(0.5f) == Approx(0.0f).margin(1e-6));
    // Three quarters of the mass: Phi^-1(0.5 + 0.25 * 0.6826895) = Phi^-1(0.67067) = 0.4418 sigma.
    CHECK(normal.sample(0.75f) == Approx(0.4418f).epsilon(1e-3));
}

TEST_CASE("Stratified light samples put one sample in each stratum", "[trace][light]") {
    for (std::uint32_t key : {0u, 12345u, 0xdeadbeefu}) {
        std::vector<int> hits(9, 0);
        PixelRng rng(7, 3, 0);
        for (std::uint32_t i = 0; i < 9; ++i) {
            float s, t;
            LightSampler::stratified_unit(i, 9, key, rng.next_float(), rng.next_float(), s, t);
            ++hits[int(t * 3) * 3 + int(s * 3)];
        }
        for (int count : hits) CHECK(count == 1);
    }
    // A count that is not a square: 10 samples over 4x3 strata, none shared.
    std::vector<int> hits(12, 0);
    for (std::uint32_t i = 0; i < 10; ++i) {
        float s, t;
        LightSampler::stratified_unit(i, 10, 99u, 0.5f, 0.5f, s, t);
        ++hits[int(t * 3) * 4 + int(s * 4)];
    }
    for (int count : hits) CHECK(count <= 1);
}

TEST_CASE("permute_index is a permutation for any count", "[trace][random]") {
    for (std::uint32_t count : {1u, 2u, 9u, 10u, 64u, 1000u})
        for (std::uint32_t key : {1u, 77u}) {
            std::vector<int> seen(count, 0);
            for (std::uint32_t i = 0; i < count; ++i) ++seen[permute_index(i, count, key)];
            for (int s : seen) REQUIRE(s == 1);
        }
}

TEST_CASE("Uniform light profile samples the rectangle uniformly", "[trace][light]") {
    LightPlane light = LightPlane::square({0, 2, 0}, {0, -1, 0}, 2.0f);
    light.profile = LightProfile::Uniform;
    const LightSampler sampler(light);
    CHECK(sampler.warp_u(0.0f) == Approx(-1.0f));
    CHECK(sampler.warp_u(0.25f) == Approx(-0.5f));
    CHECK(sampler.warp_v(1.0f) == Approx(1.0f));
}
