#include <catch2/catch.hpp>

#include <cmath>

#include "aaf/trace/shading/ggx.h"
#include "shading.h"

using namespace aaf;

// The analytic U (LTC, fitted to aaf/trace/shading/ggx.h) and the tracer's S_N, U_N
// and beauty (libaaf/trace/shading.h) must integrate the same lobe.
TEST_CASE("Ratio: the LTC's GGX lobe is the tracer's BRDF (specular part times the cosine)",
          "[trace][ratio]") {
    for (float roughness : {0.1f, 0.3f, 0.6f, 1.0f})
        for (int k = 0; k < 200; ++k) {
            // Directions spread over the upper hemisphere, deterministic.
            const float a = 0.37f * k, b = 0.11f * k + 0.5f;
            const Vec3 wo = normalize(Vec3{std::cos(a), 0.05f + std::fabs(std::sin(0.7f * k)), std::sin(a)});
            const Vec3 wi = normalize(Vec3{std::cos(b), 0.05f + std::fabs(std::cos(1.3f * k)), std::sin(b)});
            trace::Material material;
            material.albedo = {0, 0, 0};
            material.specular = {1, 1, 1};  // F = 1: no Fresnel
            material.roughness = roughness;
            const Vec3 n{0, 1, 0};
            const float tracer = trace::evaluate_brdf(material, n, wo, wi).x * dot(n, wi);
            // The same directions in a frame whose z is the normal.
            const double lobe =
                ggx::cosine_weighted({wo.x, wo.z, wo.y}, {wi.x, wi.z, wi.y}, double(roughness) * roughness);
            INFO("roughness " << roughness << ", k " << k);
            // The tracer evaluates in float: D's 1 + cos^2 (alpha^2 - 1) cancels
            // digits at the peak of a sharp lobe.
            CHECK(tracer == Approx(lobe).epsilon(1e-3).margin(1e-6));
            // Schlick's weight: F0 = 0 leaves (1 - wi.h)^5 of it.
            material.specular = {0, 0, 0};
            material.specular.x = 1e-30f;  // keeps the lobe (has_specular) with F0 ~ 0
            const float fresnel_part = trace::evaluate_brdf(material, n, wo, wi).x * dot(n, wi);
            CHECK(fresnel_part == Approx(lobe * ggx::schlick_weight({wo.x, wo.z, wo.y}, {wi.x, wi.z, wi.y}))
                                      .epsilon(1e-3)
                                      .margin(1e-6));
        }
}
