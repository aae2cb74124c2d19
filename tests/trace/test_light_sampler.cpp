#include <hwy/targets.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "../unpinned_instruction_set.h"
#include "aaf/core/util/error.h"
#include "light_sampler.h"
#include "random.h"
#include "stratified_grid.h"
#include "truncated_normal.h"

using namespace aaf;
using namespace aaf::trace;

namespace {

/// CDF of a standard normal truncated to [-limit, limit], written out here so
/// the sampler is checked against an independent formula.
double truncated_cdf(double x, double limit) {
    auto phi = [](double v) { return 0.5 * std::erfc(-v / std::sqrt(2.0)); };
    return (phi(x) - phi(-limit)) / (phi(limit) - phi(-limit));
}

}  // namespace

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
    CHECK(normal.sample(1.0f) == 1.0f);
    CHECK(normal.sample(0.5f) == Approx(0.0f).margin(1e-6));
    // Three quarters of the mass: Phi^-1(0.5 + 0.25 * 0.6826895) = Phi^-1(0.67067) = 0.4418 sigma.
    CHECK(normal.sample(0.75f) == Approx(0.4418f).epsilon(1e-3));
}

TEST_CASE("Truncated normal histogram of random draws matches the analytic masses", "[trace][light]") {
    const TruncatedNormal normal(1.0);
    constexpr int kBins = 20, kDraws = 200000;
    std::vector<int> counts(kBins, 0);
    PixelRng rng(11, 0, 0);
    for (int i = 0; i < kDraws; ++i) {
        const float x = normal.sample(rng.next_float());
        ++counts[std::min(kBins - 1, int((x + 1.0f) * 0.5f * kBins))];
    }
    for (int b = 0; b < kBins; ++b) {
        const double low = -1.0 + 2.0 * b / kBins, high = low + 2.0 / kBins;
        const double expected = kDraws * (truncated_cdf(high, 1.0) - truncated_cdf(low, 1.0));
        INFO("bin " << b);
        CHECK(std::fabs(counts[b] - expected) < 5 * std::sqrt(expected));  // five standard deviations
    }
}

TEST_CASE("Truncated normal inverse is accurate, monotone and never NaN", "[trace][light]") {
    for (double limit : {0.25, 1.0, 3.0, 8.0}) {
        INFO("limit " << limit);
        const TruncatedNormal normal(limit);
        float previous = -std::numeric_limits<float>::infinity();
        double worst = 0;
        for (int i = 0; i <= 100000; ++i) {
            const float u = std::min(float(i) / 100000.0f, 0x1.fffffep-1f);
            const float x = normal.sample(u);
            REQUIRE(x >= previous);
            REQUIRE(std::fabs(x) <= float(limit));
            previous = x;
            worst = std::max(worst, std::fabs(truncated_cdf(x, limit) - double(u)));
        }
        CHECK(worst < 1e-6);
        CHECK(normal.sample(std::numeric_limits<float>::quiet_NaN()) == float(-limit));
        CHECK(normal.inverse_cdf(0.3) == Approx(normal.sample(0.3f)).margin(1e-6));
        CHECK(truncated_cdf(normal.inverse_cdf(0.3), limit) == Approx(0.3).margin(1e-12));
    }
    CHECK_THROWS_AS(TruncatedNormal(0.0), Error);
    CHECK_THROWS_AS(TruncatedNormal(9.0), Error);
    CHECK_THROWS_AS(TruncatedNormal(std::numeric_limits<double>::quiet_NaN()), Error);
}

TEST_CASE("Stratified grid puts one sample in each of the 3x3 strata for 9 samples", "[trace][light]") {
    const StratifiedGrid grid(9);
    REQUIRE(grid.columns() == 3);
    REQUIRE(grid.rows() == 3);
    for (std::uint32_t key : {0u, 12345u, 0xdeadbeefu}) {
        std::vector<int> hits(9, 0);
        PixelRng rng(7, key, 0);
        for (std::uint32_t i = 0; i < 9; ++i) {
            const UnitPoint p = grid.point(i, key, rng.next_float(), rng.next_float());
            REQUIRE(p.s >= 0.0f);
            REQUIRE(p.s < 1.0f);
            REQUIRE(p.t >= 0.0f);
            REQUIRE(p.t < 1.0f);
            ++hits[int(p.t * 3) * 3 + int(p.s * 3)];
        }
        for (int count : hits) CHECK(count == 1);
    }
}

TEST_CASE("Stratified grid spreads a non-square count over distinct strata", "[trace][light]") {
    // 10 samples: 4 columns x 3 rows; no stratum twice, and over many pixels every stratum is used.
    const StratifiedGrid grid(10);
    REQUIRE(grid.columns() == 4);
    REQUIRE(grid.rows() == 3);
    std::vector<int> used(12, 0);
    for (std::uint64_t pixel = 0; pixel < 64; ++pixel) {
        const std::uint32_t key = PixelRng(1, pixel, 0).next_u32();
        std::vector<int> hits(12, 0);
        for (std::uint32_t i = 0; i < 10; ++i) {
            const UnitPoint p = grid.point(i, key, 0.5f, 0.5f);
            ++hits[int(p.t * 3) * 4 + int(p.s * 4)];
        }
        for (int s = 0; s < 12; ++s) {
            CHECK(hits[s] <= 1);
            used[s] += hits[s];
        }
    }
    for (int count : used) CHECK(count > 0);
    // The top edge stays inside the square despite float rounding.
    const UnitPoint corner = StratifiedGrid(1).point(0, 0, 0x1.fffffep-1f, 0x1.fffffep-1f);
    CHECK(corner.s < 1.0f);
    CHECK(corner.t < 1.0f);
}

TEST_CASE("permute_index is a permutation for any count", "[trace][random]") {
    for (std::uint32_t count : {1u, 2u, 9u, 10u, 64u, 1000u})
        for (std::uint32_t key : {1u, 77u}) {
            std::vector<int> seen(count, 0);
            for (std::uint32_t i = 0; i < count; ++i) ++seen[permute_index(i, count, key)];
            for (int s : seen) REQUIRE(s == 1);
        }
}

TEST_CASE("Gaussian light samples stay on the rectangle with the truncated moments", "[trace][light]") {
    // Side 2 m, so sigma = 1 m and the Gaussian is cut at 1 sigma.
    const LightPlane light = LightPlane::square({0, 2, 0}, {0, -1, 0}, 2.0f);
    const LightSampler sampler(light);
    const StratifiedGrid grid(16);
    double sum_u = 0, sum_u_sq = 0, sum_v_sq = 0;
    int n = 0;
    for (std::uint64_t pixel = 0; pixel < 4000; ++pixel) {
        PixelRng rng(5, pixel, 0);
        const std::uint32_t key = rng.next_u32();
        for (std::uint32_t i = 0; i < 16; ++i) {
            const Vec3 y = sampler.point(grid.point(i, key, rng.next_float(), rng.next_float()));
            const double u = dot(y - light.center, light.axis_u), v = dot(y - light.center, light.axis_v);
            REQUIRE(std::fabs(u) <= 1.0 + 1e-6);
            REQUIRE(std::fabs(v) <= 1.0 + 1e-6);
            REQUIRE(light.plane_distance_m(y) < 1e-6f);
            sum_u += u;
            sum_u_sq += u * u;
            sum_v_sq += v * v;
            ++n;
        }
    }
    CHECK(sum_u / n == Approx(0.0).margin(0.005));
    CHECK(sum_u_sq / n == Approx(0.2911).epsilon(0.01));
    CHECK(sum_v_sq / n == Approx(0.2911).epsilon(0.01));
}

TEST_CASE("Uniform light profile samples the rectangle uniformly", "[trace][light]") {
    LightPlane light = LightPlane::square({0, 2, 0}, {0, -1, 0}, 2.0f);
    light.profile = LightProfile::Uniform;
    const LightSampler sampler(light);
    CHECK(sampler.warp_u(0.0f) == Approx(-1.0f));
    CHECK(sampler.warp_u(0.25f) == Approx(-0.5f));
    CHECK(sampler.warp_v(1.0f) == Approx(1.0f));
    // A uniform light needs no Gaussian truncation, however small its sigma.
    light.sigma_m = 0.01f;
    CHECK_NOTHROW(LightSampler(light));
}

TEST_CASE("Stratified grid finds a stratum's row without integer division, exactly", "[trace][light]") {
    // Every stratum of grids up to 2^20 samples (the largest count a pixel takes).
    for (std::uint32_t count : {1u, 2u, 9u, 10u, 1000u, 1024u, 4097u, 65536u, 100000u, 1u << 20}) {
        const StratifiedGrid grid(count);
        INFO("count " << count << ", columns " << grid.columns());
        std::uint32_t wrong = 0;
        for (std::uint32_t s = 0; s < grid.columns() * grid.rows(); ++s)
            wrong += grid.row_of(s) != s / grid.columns();
        CHECK(wrong == 0);
    }
}

TEST_CASE("The batched light warp gives warp_u and warp_v's bits", "[trace][light]") {
    const aaf_test::UnpinnedInstructionSet every_target;  // the test walks Highway's targets itself
    // Inputs over every interval of the inverse-CDF table, with the edges and
    // invalid values sample() maps to the truncation limits.
    std::vector<float> s, t;
    for (int i = 0; i < 4 * TruncatedNormal::kIntervals; ++i) {
        s.push_back((float(i) + 0.37f) / float(4 * TruncatedNormal::kIntervals));
        t.push_back(1.0f - s.back());
    }
    for (float edge : {0.0f, -0.0f, 1.0f, 0x1.fffffep-1f, 1e-30f, 1e-7f, -1.0f, 2.0f,
                       std::numeric_limits<float>::quiet_NaN()}) {
        s.push_back(edge);
        t.push_back(edge);
    }
    auto bits = [](float x) {
        std::uint32_t b;
        std::memcpy(&b, &x, sizeof b);
        return b;
    };
    // Square and oblong Gaussians (the oblong one cut at 8 sigma along u,
    // where the table's tails fall back to the exact inverse) and a uniform light.
    LightPlane square = LightPlane::square({0, 2, 0}, {0, -1, 0}, 2.0f);
    LightPlane oblong = square;
    oblong.height_m = 0.5f;
    oblong.sigma_m = 0.125f;
    LightPlane uniform = square;
    uniform.profile = LightProfile::Uniform;
    // On every instruction set the vectorised warp is built for, and with a
    // batch length that leaves a tail shorter than a vector.
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);
        for (const LightPlane &light : {square, oblong, uniform}) {
            const LightSampler sampler(light);
            for (const std::size_t count : {s.size(), std::size_t(13)}) {
                std::vector<float> u_m(count), v_m(count);
                sampler.warp(s.data() + s.size() - count, t.data() + s.size() - count, count, u_m.data(),
                             v_m.data());
                std::size_t differing = 0;
                for (std::size_t k = 0; k < count; ++k) {
                    const std::size_t i = s.size() - count + k;
                    differing += bits(u_m[k]) != bits(sampler.warp_u(s[i])) ||
                                 bits(v_m[k]) != bits(sampler.warp_v(t[i]));
                }
                INFO("target " << hwy::TargetName(target) << ", " << count << " points");
                CHECK(differing == 0);
            }
        }
    }
    hwy::SetSupportedTargetsForTest(0);
}
