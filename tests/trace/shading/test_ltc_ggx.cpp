#include <catch2/catch.hpp>

#include <cmath>

#include "aaf/trace/shading/ggx.h"
#include "aaf/trace/shading/ltc_ggx.h"
#include "ltc_reference.h"

using namespace aaf;

namespace {

constexpr double kPi = 3.14159265358979323846;
const double kRoughness[] = {0.3, 0.5, 0.7, 1.0};
const double kViewDeg[] = {0, 30, 60, 75};
// The documented fit error (scripts/ltc_fit/README.md, "LTC fit error"; the
// rows and columns above), rounded up at the 4th decimal: the highlight's
// relative error and the largest absolute error over the placements as a
// fraction of the lobe's hemispherical integral, F0 = 1 and F0 = 0.
const double kHighlight[4][4] = {{0.0049, 0.0025, 0.0016, 0.0296},
                                 {0.0017, 0.0079, 0.0430, 0.1863},
                                 {0.0134, 0.0202, 0.0808, 0.1264},
                                 {0.0289, 0.0060, 0.0193, 0.0356}};
const double kLobe[4][4] = {{0.0045, 0.0018, 0.0247, 0.0636},
                            {0.0027, 0.0084, 0.0358, 0.0777},
                            {0.0028, 0.0090, 0.0154, 0.0232},
                            {0.0025, 0.0025, 0.0025, 0.0025}};
const double kFresnel[4][4] = {{0.0000, 0.0000, 0.0022, 0.0258},
                               {0.0000, 0.0002, 0.0057, 0.0255},
                               {0.0000, 0.0004, 0.0039, 0.0100},
                               {0.0000, 0.0000, 0.0004, 0.0009}};
constexpr double kRounding = 1e-4;

}  // namespace

TEST_CASE("LTC GGX: polygon integrals match brute-force quadrature within the documented fit error",
          "[ratio][ltc]") {
    for (int r = 0; r < 4; ++r)
        for (int v = 0; v < 4; ++v) {
            const double theta = kViewDeg[v] * kPi / 180;
            const Vec3d wo{std::sin(theta), 0, std::cos(theta)};
            const double magnitude = ltc_ggx::lookup(kRoughness[r], wo.z).magnitude;
            const auto lights = ltc_reference::ggx_placements(kViewDeg[v]);
            for (std::size_t k = 0; k < lights.size(); ++k) {
                INFO("roughness " << kRoughness[r] << ", view " << kViewDeg[v] << " deg, placement " << k);
                const ltc_ggx::PolygonIntegral ltc =
                    ltc_ggx::integrate(lights[k].polygon(), kRoughness[r], wo.z);
                const double lobe = ltc_reference::ggx_by_quadrature(lights[k], wo, kRoughness[r], false);
                const double fresnel = ltc_reference::ggx_by_quadrature(lights[k], wo, kRoughness[r], true);
                REQUIRE(lobe > 0);
                CHECK(std::fabs(ltc.magnitude_term - lobe) <= (kLobe[r][v] + kRounding) * magnitude);
                CHECK(std::fabs(ltc.fresnel_term - fresnel) <= (kFresnel[r][v] + kRounding) * magnitude);
                if (k == 0)
                    CHECK(std::fabs(ltc.magnitude_term - lobe) <= (kHighlight[r][v] + kRounding) * lobe);
            }
        }
}

TEST_CASE("LTC GGX: the table's magnitude is the lobe's hemispherical integral, zero below the horizon",
          "[ratio][ltc]") {
    // A light covering the whole upper hemisphere (a huge square just above
    // the point) collects the lobe's whole hemispherical integral at normal
    // view; at oblique views the LTC (normalised over the sphere) puts part of
    // its mass below the horizon, so it collects less, never more.
    const ltc_reference::Rectangle sky = ltc_reference::facing_square({0, 0, 1}, 1e-3, 1e4);
    for (double roughness : {0.3, 0.6, 1.0}) {
        const ltc_ggx::PolygonIntegral normal = ltc_ggx::integrate(sky.polygon(), roughness, 1.0);
        CHECK(normal.magnitude_term == Approx(ltc_ggx::lookup(roughness, 1.0).magnitude).epsilon(1e-4));
        for (double view_deg : {30.0, 60.0, 80.0}) {
            const double cos_view = std::cos(view_deg * kPi / 180);
            const ltc_ggx::PolygonIntegral all = ltc_ggx::integrate(sky.polygon(), roughness, cos_view);
            CHECK(all.magnitude_term <= ltc_ggx::lookup(roughness, cos_view).magnitude * (1 + 1e-6));
            CHECK(all.magnitude_term > 0);
        }
    }
    const ltc_reference::Rectangle below{{1.0, -0.5, -1.5}, {0, 0, 1.0}, {0, 1.0, 0}};
    const ltc_ggx::PolygonIntegral none = ltc_ggx::integrate(below.polygon(), 0.5, 0.8);
    CHECK(none.magnitude_term == 0);
    CHECK(none.fresnel_term == 0);
    // A view below the horizon has no specular lobe.
    CHECK(ltc_ggx::integrate(sky.polygon(), 0.5, -0.1).magnitude_term == 0);
}
