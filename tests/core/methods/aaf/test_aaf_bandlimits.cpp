#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "aaf/core/methods/aaf/aaf_bandlimits.h"

using aaf::aaf_bandlimits;
using aaf::aaf_bandlimits_axes;
using aaf::AafAxisBandlimits;
using aaf::AafBandlimits;
using aaf::AafParams;
using aaf::LightBandlimitAxes;
using aaf::mu_for_samples;

TEST_CASE("AAF slopes, bandlimits and beta match hand-computed values", "[aaf][bandlimits]") {
    // d1 = 2 m, d2min = 0.5 m, d2max = 1 m, d = 1 cm, sigma = 0.5 m, paper defaults.
    // s1 = 2/0.5 - 1 = 3, s2 = 2/1 - 1 = 1 (Eq. 4); Omega_L = 2; Omega_x^max = 100/2 = 50 (Eq. 6);
    // Omega_y^max = (1 - 0.25) 100 = 75 (Eq. 7); Omega_x0^f = min(2/1, 50) = 2 (Eq. 8);
    // beta = 1/(3 * 2 * 2) = 1/12 m (Eq. 13).
    const auto b = aaf_bandlimits(2.0f, 0.5f, 1.0f, 0.01f, 0.5f, AafParams{});
    CHECK(b.s1 == Approx(3.0f));
    CHECK(b.s2 == Approx(1.0f));
    CHECK(b.omega_light == Approx(2.0f));
    CHECK(b.omega_x_max == Approx(50.0f));
    CHECK(b.omega_y_max == Approx(75.0f));
    CHECK(b.omega_x_f0 == Approx(2.0f));
    CHECK(b.beta_m == Approx(1.0f / 12.0f));
    // Eq. 21: n = 4 (1 + mu s1/s2)^2 (mu (2/s2) sqrt(A_p/A_l) + alpha/(1+s2))^2
    //           = 4 * 49 * (0.04 + 0.5)^2 = 57.1536
    CHECK(b.samples_per_pixel == Approx(57.1536f).epsilon(1e-4));
}

TEST_CASE("AAF beta follows Eq. 13 in closed form", "[aaf][bandlimits]") {
    AafParams params;
    params.mu = 1.5f;
    params.k = 2.0f;
    params.alpha = 0.8f;
    const float d1 = 3.0f, d2_max = 2.0f, pixel = 0.004f, sigma = 0.3f;
    const float s2 = d1 / d2_max - 1.0f;
    const float omega_x_max = params.alpha / (1.0f + s2) / pixel;
    const float expected = 1.0f / (params.k * params.mu) * std::max(sigma * s2, 1.0f / omega_x_max);
    CHECK(aaf_bandlimits(d1, 1.0f, d2_max, pixel, sigma, params).beta_m == Approx(expected));
}

TEST_CASE("AAF beta is clipped by the pixel bandlimit for small lights and near contact",
          "[aaf][bandlimits]") {
    // sigma = 5 mm: Omega_L / s2 = 200 / 0.0526 = 3800 > Omega_x^max = 95, so Eq. 8 clips:
    // beta = (1 + s2) d / (alpha k mu) = 1.0526 * 0.01 / 6.
    const auto clipped = aaf_bandlimits(2.0f, 1.9f, 1.9f, 0.01f, 0.005f, AafParams{});
    CHECK(clipped.omega_x_f0 == Approx(clipped.omega_x_max));
    CHECK(clipped.beta_m == Approx((2.0f / 1.9f) * 0.01f / 6.0f));

    // Contact (d2max = d1, s2 = 0): finite beta of a sixth of a pixel and finite n.
    const auto contact = aaf_bandlimits(2.0f, 1.0f, 2.0f, 0.01f, 0.5f, AafParams{});
    CHECK(contact.s2 == 0.0f);
    CHECK(contact.beta_m == Approx(0.01f / 6.0f));
    CHECK(std::isfinite(contact.samples_per_pixel));
}

TEST_CASE("AAF beta scales as 1/mu and sampling rate grows with mu (consistency)", "[aaf][bandlimits]") {
    AafParams low, high;
    low.mu = 1.0f;
    high.mu = 4.0f;
    const auto a = aaf_bandlimits(2.0f, 0.6f, 1.2f, 0.01f, 0.5f, low);
    const auto b = aaf_bandlimits(2.0f, 0.6f, 1.2f, 0.01f, 0.5f, high);
    CHECK(b.beta_m == Approx(a.beta_m / 4.0f));
    CHECK(b.samples_per_pixel > a.samples_per_pixel);
}

TEST_CASE("AAF slopes are never negative when an occluder is measured beyond the receiver",
          "[aaf][bandlimits]") {
    const auto b = aaf_bandlimits(1.0f, 1.2f, 1.3f, 0.01f, 0.5f, AafParams{});
    CHECK(b.s1 == 0.0f);
    CHECK(b.s2 == 0.0f);
    CHECK(b.beta_m > 0.0f);
}

TEST_CASE(
    "AAF per light axis: equal sigmas give the isotropic analysis, unequal ones a beta and rate per axis",
    "[aaf][bandlimits]") {
    AafParams params;
    const float d1 = 2.0f, d2_min = 1.0f, d2_max = 1.5f, pixel = 0.01f;
    const AafBandlimits iso = aaf_bandlimits(d1, d2_min, d2_max, pixel, 0.3f, params);
    const AafAxisBandlimits same = aaf_bandlimits_axes(d1, d2_min, d2_max, pixel, {0.3f, 0.3f}, params);
    CHECK(same.u.beta_m == iso.beta_m);
    CHECK(same.v.beta_m == iso.beta_m);
    CHECK(same.samples_per_pixel == iso.samples_per_pixel);

    const AafBandlimits long_axis = aaf_bandlimits(d1, d2_min, d2_max, pixel, 0.6f, params);
    const AafAxisBandlimits both = aaf_bandlimits_axes(d1, d2_min, d2_max, pixel, {0.6f, 0.3f}, params);
    // AAF Eq. 8 and 13 per axis: the longer axis (larger sigma, lower band-limit) blurs more.
    CHECK(both.u.beta_m == long_axis.beta_m);
    CHECK(both.v.beta_m == iso.beta_m);
    CHECK(both.u.beta_m > both.v.beta_m);
    // AAF Eq. 15 per axis: the rate is the product of the axes' factors, the
    // geometric mean of the two isotropic rates.
    CHECK(
        both.samples_per_pixel ==
        Approx(std::sqrt(double(iso.samples_per_pixel) * double(long_axis.samples_per_pixel))).epsilon(1e-5));

    // mu from spp inverts the per-axis rate.
    const float samples = 3 * both.samples_per_pixel;
    const float mu =
        mu_for_samples(samples, d1, d2_min, d2_max, pixel, LightBandlimitAxes{0.6f, 0.3f}, params);
    AafParams at_mu = params;
    at_mu.mu = mu;
    CHECK(aaf_bandlimits_axes(d1, d2_min, d2_max, pixel, {0.6f, 0.3f}, at_mu).samples_per_pixel ==
          Approx(samples).epsilon(1e-3));
}

namespace {

// AAF Eq. 4-8, 13 and 15 written out in one piece, as aaf_bandlimits() had
// them before its mu-free terms were split off for mu_for_samples().
AafBandlimits one_piece_bandlimits(float d1, float d2_min, float d2_max, float pixel, float sigma,
                                   const AafParams &params) {
    AafBandlimits b;
    b.s1 = std::max(0.0f, d1 / d2_min - 1.0f);
    b.s2 = std::max(0.0f, d1 / d2_max - 1.0f);
    b.omega_light = 1.0f / sigma;
    const float omega_pixel = 1.0f / pixel;
    b.omega_x_max = params.alpha / (1.0f + b.s2) * omega_pixel;
    b.omega_y_max = params.alpha * std::max(0.0f, 1.0f - d2_min / d1) * omega_pixel;
    const float light_induced = b.s2 > 0 ? b.omega_light / b.s2 : std::numeric_limits<float>::infinity();
    b.omega_x_f0 = std::min(light_induced, b.omega_x_max);
    b.omega_x_f = params.mu * b.omega_x_f0;
    b.beta_m = 1.0f / (params.k * b.omega_x_f);
    const float omega_x_star = b.omega_x_f + b.omega_x_max;
    const float omega_y_star = b.omega_light + std::min(b.s1 * b.omega_x_f, b.omega_y_max);
    const float pixel_term = omega_x_star * pixel;
    const float light_term = omega_y_star * 2.0f * sigma;
    b.samples_per_pixel = pixel_term * pixel_term * light_term * light_term;
    return b;
}

// mu_for_samples() as its contract defines it: the bisection evaluating the
// whole per-axis analysis at every step.
float bisected_mu(float samples, float d1, float d2_min, float d2_max, float pixel, LightBandlimitAxes sigma,
                  const AafParams &params) {
    AafParams trial = params;
    auto rate = [&](float mu) {
        trial.mu = mu;
        const AafBandlimits u = one_piece_bandlimits(d1, d2_min, d2_max, pixel, sigma.u_m, trial);
        if (sigma.v_m == sigma.u_m) return u.samples_per_pixel;
        const AafBandlimits v = one_piece_bandlimits(d1, d2_min, d2_max, pixel, sigma.v_m, trial);
        return std::sqrt(u.samples_per_pixel) * std::sqrt(v.samples_per_pixel);
    };
    if (!(rate(params.mu) < samples)) return params.mu;
    if (rate(1e4f) <= samples) return 1e4f;
    float low = params.mu, high = 1e4f;
    while (high - low > 1e-4f * low) {
        const float mid = std::sqrt(low * high);
        (rate(mid) < samples ? low : high) = mid;
    }
    return low;
}

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

TEST_CASE("bandlimits and mu from spp give the one-piece evaluation's bits", "[aaf][bandlimits][mu]") {
    std::mt19937 rng(18);
    auto log_uniform = [&](float lo, float hi) {
        return lo * std::pow(hi / lo, std::uniform_real_distribution<float>(0.0f, 1.0f)(rng));
    };
    int bisected = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const float d1 = log_uniform(0.01f, 20.0f);
        // Occluders from grazing contact to near the light, some measured beyond the receiver.
        const float d2_max = d1 * log_uniform(0.01f, 1.2f);
        const float d2_min = trial % 7 == 0 ? d2_max : d2_max * log_uniform(0.05f, 1.0f);
        const float pixel = log_uniform(1e-5f, 0.1f);
        const float sigma_u = log_uniform(0.01f, 2.0f);
        const float sigma_v = trial % 3 == 0 ? sigma_u : log_uniform(0.01f, 2.0f);
        AafParams params;
        params.mu = log_uniform(0.5f, 4.0f);
        params.k = log_uniform(1.0f, 5.0f);
        params.alpha = log_uniform(0.3f, 1.0f);
        const float samples = log_uniform(0.5f, 2000.0f);

        const AafBandlimits b = aaf_bandlimits(d1, d2_min, d2_max, pixel, sigma_u, params);
        const AafBandlimits ref = one_piece_bandlimits(d1, d2_min, d2_max, pixel, sigma_u, params);
        CHECK(same_bits(b.omega_x_f, ref.omega_x_f));
        CHECK(same_bits(b.beta_m, ref.beta_m));
        CHECK(same_bits(b.samples_per_pixel, ref.samples_per_pixel));

        const LightBandlimitAxes sigma{sigma_u, sigma_v};
        const float mu = mu_for_samples(samples, d1, d2_min, d2_max, pixel, sigma, params);
        const float expected = bisected_mu(samples, d1, d2_min, d2_max, pixel, sigma, params);
        if (!same_bits(mu, expected)) FAIL_CHECK("trial " << trial << ": mu " << mu << " vs " << expected);
        if (expected != params.mu && expected != 1e4f) ++bisected;
    }
    // Most draws must reach the bisection itself, not only its two early exits.
    CHECK(bisected > 10000);
}
