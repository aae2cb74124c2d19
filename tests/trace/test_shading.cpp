#include <catch2/catch.hpp>

#include <cmath>

#include "shading.h"

using namespace aaf;

namespace {

/// Directional albedo: the integral of f cos(theta_i) over the hemisphere,
/// by a midpoint rule in (cos theta, phi).
double directional_albedo(const trace::Material &material, Vec3 wo) {
    constexpr int kSteps = 400;
    const Vec3 n{0, 0, 1};
    double sum = 0;
    for (int i = 0; i < kSteps; ++i)
        for (int j = 0; j < kSteps; ++j) {
            const double cos_theta = (i + 0.5) / kSteps, phi = 2 * 3.14159265358979 * (j + 0.5) / kSteps;
            const double sin_theta = std::sqrt(1 - cos_theta * cos_theta);
            const Vec3 wi{float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)),
                          float(cos_theta)};
            sum += trace::evaluate_brdf(material, n, wo, wi).x * cos_theta;
        }
    return sum * (1.0 / kSteps) * (2 * 3.14159265358979 / kSteps);
}

}  // namespace

TEST_CASE("Lambert's directional albedo is its albedo", "[trace][shading]") {
    trace::Material lambert;
    lambert.albedo = {0.6f, 0.6f, 0.6f};
    CHECK(directional_albedo(lambert, {0, 0, 1}) == Approx(0.6).epsilon(1e-3));
}

TEST_CASE("A GGX lobe with Fresnel 1 has the directional albedo of an independent estimate",
          "[trace][shading]") {
    trace::Material metal;
    metal.albedo = {0, 0, 0};
    metal.specular = {1, 1, 1};  // Fresnel = 1: only masking-shadowing loses energy
    // At normal incidence, by importance-sampling D(h) cos(h) and averaging
    // G1(wi) G1(wo) (wo.h) / (cos_o cos_h) (400k samples, a separate script):
    // 0.9906 for roughness 0.3 and 0.8253 for 0.6 (separable Smith masking).
    const std::pair<float, double> expected[] = {{0.3f, 0.9906}, {0.6f, 0.8253}};
    for (const auto &[roughness, albedo] : expected) {
        metal.roughness = roughness;
        INFO("roughness " << roughness);
        const double measured = directional_albedo(metal, {0, 0, 1});
        CHECK(measured <= 1.0);
        CHECK(measured == Approx(albedo).epsilon(0.005));
    }
    // The lobe peaks in the mirror direction.
    metal.roughness = 0.3f;
    const Vec3 wo = normalize(Vec3{0.5f, 0, 1});
    const Vec3 mirror{-wo.x, -wo.y, wo.z};
    const Vec3 off = normalize(Vec3{0.2f, 0.4f, 1});
    CHECK(trace::evaluate_brdf(metal, {0, 0, 1}, wo, mirror).x >
          5 * trace::evaluate_brdf(metal, {0, 0, 1}, wo, off).x);
}
