#include <catch2/catch.hpp>

#include <cmath>

#include "spherical_rectangle.h"

using namespace aaf;

namespace {

/// Samples on a g x g grid of the unit square whose light point lies at u
/// below `u_limit_m` metres (from the light's centre along axis_u).
double share_below(const trace::SphericalRectangle &rectangle, const LightPlane &light, double u_limit_m,
                   int g) {
    int below = 0;
    for (int j = 0; j < g; ++j)
        for (int i = 0; i < g; ++i) {
            const Vec3d y = rectangle.sample((i + 0.5) / g, (j + 0.5) / g);
            const double u = (y.x - light.center.x) * light.axis_u.x +
                             (y.y - light.center.y) * light.axis_u.y +
                             (y.z - light.center.z) * light.axis_u.z;
            below += u < u_limit_m;
        }
    return double(below) / (double(g) * g);
}

}  // namespace

TEST_CASE("Spherical rectangle: samples lie on the light, uniform in solid angle (Urena et al. 2013)",
          "[trace][ratio][sampling]") {
    LightPlane light = LightPlane::square({0.3f, 2.0f, -0.2f}, {0, -1, 0}, 1.0f);
    light.width_m = 1.6f;
    light.height_m = 0.8f;
    const Vec3d p{-0.4, 0.0, 0.5};
    const trace::SphericalRectangle rectangle(light, p);
    REQUIRE(rectangle.visible());
    REQUIRE(rectangle.uses_solid_angle());
    for (int k = 0; k < 100; ++k) {
        const Vec3d y = rectangle.sample((k % 10 + 0.5) / 10, (k / 10 + 0.5) / 10);
        CHECK(std::fabs(y.y - 2.0) < 1e-9);
        CHECK(std::fabs(y.x - 0.3) <= 0.8 + 1e-9);
        CHECK(std::fabs(y.z + 0.2) <= 0.4 + 1e-9);
        Vec3d hit;
        CHECK(rectangle.intersect(normalize(y - p), hit));
        CHECK(length(hit - y) < 1e-9);
    }
    // The share of samples on the light's part u < u0 equals that part's
    // solid angle over the whole one.
    for (double u0 : {-0.5, 0.0, 0.4}) {
        LightPlane part = light;
        part.width_m = float(u0 + 0.8);
        part.center = {float(0.3 - 0.8 + part.width_m / 2), 2.0f, -0.2f};
        const trace::SphericalRectangle part_rectangle(part, p);
        INFO("u0 = " << u0);
        CHECK(share_below(rectangle, light, u0, 256) ==
              Approx(part_rectangle.solid_angle_sr() / rectangle.solid_angle_sr()).margin(2.0 / 256));
    }
    CHECK(rectangle.pdf(rectangle.sample(0.3, 0.6)) == Approx(1 / rectangle.solid_angle_sr()));
}

TEST_CASE("Spherical rectangle: tiny and grazing lights fall back to area sampling with the solid-angle pdf",
          "[trace][ratio][sampling]") {
    // 1 cm at 100 m: about 1e-8 sr.
    const LightPlane tiny = LightPlane::square({0, 100, 0}, {0, -1, 0}, 0.01f);
    const trace::SphericalRectangle far(tiny, {0, 0, 0});
    REQUIRE(far.visible());
    CHECK_FALSE(far.uses_solid_angle());
    // pdf = r^2 / (A cos): at the centre 100^2 / 1e-4.
    CHECK(far.pdf({0, 100, 0}) == Approx(1e8).epsilon(1e-5));
    // Grazing: a point 1e-6 m in front of the light's plane.
    const LightPlane big = LightPlane::square({0, 1, 0}, {0, -1, 0}, 1.0f);
    const trace::SphericalRectangle grazing(big, {2.0, 1.0 - 1e-6, 0});
    REQUIRE(grazing.visible());
    CHECK_FALSE(grazing.uses_solid_angle());
    const Vec3d y = grazing.sample(0.5, 0.5);
    CHECK(std::isfinite(grazing.pdf(y)));
    // Behind the emitting side: nothing to sample.
    CHECK_FALSE(trace::SphericalRectangle(big, {0, 2, 0}).visible());
}
