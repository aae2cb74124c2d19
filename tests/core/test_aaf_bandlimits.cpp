#include <catch2/catch.hpp>
#include <cmath>

#include "aaf/core/aaf_bandlimits.h"

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
