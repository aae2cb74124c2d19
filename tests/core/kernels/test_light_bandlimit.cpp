#include <catch2/catch.hpp>

#include <cmath>

#include "aaf/core/kernels/light_bandlimit.h"
#include "aaf/core/util/error.h"

using namespace aaf;

namespace {

LightPlane rectangle(float width_m, float height_m, float sigma_m, LightProfile profile) {
    LightPlane light = LightPlane::square(Vec3{0, 3, 0}, Vec3{0, -1, 0}, 1.0f);
    light.width_m = width_m;
    light.height_m = height_m;
    light.sigma_m = sigma_m;
    light.profile = profile;
    return light;
}

}  // namespace

TEST_CASE("An untruncated Gaussian light keeps its sigma under every rule", "[aaf][light]") {
    const LightPlane light = rectangle(8.0f, 8.0f, 0.5f, LightProfile::Gaussian);  // edges at 8 sigma
    for (LightBandlimit rule :
         {LightBandlimit::Sigma, LightBandlimit::Spectrum, LightBandlimit::EquivalentWidth})
        CHECK(light_bandlimit_sigma_m(light, rule) == Approx(0.5f));
}

TEST_CASE("A uniform light's band-limit: its sinc spectrum falls to exp(-1/2) at 1/sigma_b", "[aaf][light]") {
    const float half_m = 0.4f;
    const LightPlane light = rectangle(2 * half_m, 2 * half_m, 0.4f, LightProfile::Uniform);
    const double sigma_b = light_bandlimit_sigma_m(light, LightBandlimit::Spectrum);
    const double x = half_m / sigma_b;  // the box's spectrum is sin(omega h) / (omega h)
    CHECK(std::sin(x) / x == Approx(std::exp(-0.5)).epsilon(1e-4));
    // Equivalent width: 2h / sqrt(2 pi).
    CHECK(light_bandlimit_sigma_m(light, LightBandlimit::EquivalentWidth) ==
          Approx(2 * half_m / std::sqrt(2 * 3.14159265358979)));
}

TEST_CASE("The default square light (edges at 1 sigma) is band-limited at 1.77 / sigma", "[aaf][light]") {
    const LightPlane light = LightPlane::square(Vec3{0, 3, 0}, Vec3{0, -1, 0}, 1.0f);  // sigma 0.5 m
    const double sigma_b = light_bandlimit_sigma_m(light, LightBandlimit::Spectrum);
    // The truncated profile's spectrum at 1/sigma_b by a fine midpoint sum.
    double numerator = 0, denominator = 0;
    for (int i = 0; i < 100000; ++i) {
        const double x = -0.5 + (i + 0.5) * 1e-5;
        const double p = std::exp(-x * x / (2 * 0.25));
        numerator += p * std::cos(x / sigma_b);
        denominator += p;
    }
    CHECK(numerator / denominator == Approx(std::exp(-0.5)).epsilon(1e-4));
    CHECK(sigma_b / 0.5 == Approx(0.5649).epsilon(1e-3));  // sigma_b = 0.565 sigma
    // Equivalent width: sigma erf(1 / sqrt 2) = 0.683 sigma; the paper's reading: sigma.
    CHECK(light_bandlimit_sigma_m(light, LightBandlimit::EquivalentWidth) ==
          Approx(0.5 * std::erf(1 / std::sqrt(2.0))));
    CHECK(light_bandlimit_sigma_m(light, LightBandlimit::Sigma) == 0.5f);
}

TEST_CASE("A rectangle's band-limit is its narrower axis's", "[aaf][light]") {
    const LightPlane wide = rectangle(2.0f, 0.5f, 0.25f, LightProfile::Gaussian);
    const LightPlane narrow = rectangle(0.5f, 0.5f, 0.25f, LightProfile::Gaussian);
    CHECK(light_bandlimit_sigma_m(wide, LightBandlimit::Spectrum) ==
          Approx(light_bandlimit_sigma_m(narrow, LightBandlimit::Spectrum)));
    CHECK(light_bandlimit_sigma_m(narrow, LightBandlimit::Spectrum) < 0.25f);
    CHECK_THROWS_AS(light_bandlimit_from_string("box"), Error);
    CHECK(light_bandlimit_from_string(to_string(LightBandlimit::EquivalentWidth)) ==
          LightBandlimit::EquivalentWidth);
}

TEST_CASE("Each axis of a rectangle has its own band-limit, from its own half-extent", "[aaf][light]") {
    // 2 m x 0.5 m at sigma 0.25: the long axis is cut at 4 sigma, the short at 1 sigma.
    const LightPlane wide = rectangle(2.0f, 0.5f, 0.25f, LightProfile::Gaussian);
    const LightBandlimitAxes axes = light_bandlimit_axes_m(wide, LightBandlimit::EquivalentWidth);
    CHECK(axes.u_m == Approx(0.25 * std::erf(4 / std::sqrt(2.0))));
    CHECK(axes.v_m == Approx(0.25 * std::erf(1 / std::sqrt(2.0))));
    CHECK(light_bandlimit_sigma_m(wide, LightBandlimit::EquivalentWidth) == std::min(axes.u_m, axes.v_m));
    // Turning the rectangle swaps the axes.
    const LightBandlimitAxes turned = light_bandlimit_axes_m(
        rectangle(0.5f, 2.0f, 0.25f, LightProfile::Gaussian), LightBandlimit::Spectrum);
    const LightBandlimitAxes straight = light_bandlimit_axes_m(wide, LightBandlimit::Spectrum);
    CHECK(turned.u_m == straight.v_m);
    CHECK(turned.v_m == straight.u_m);
    // The paper's reading has one sigma for both.
    const LightBandlimitAxes paper = light_bandlimit_axes_m(wide, LightBandlimit::Sigma);
    CHECK(paper.u_m == 0.25f);
    CHECK(paper.v_m == 0.25f);
}
