#include <catch2/catch.hpp>

#include <cmath>

#include "aaf/core/contract/light_plane.h"
#include "aaf/trace/shading/polygon_irradiance.h"
#include "aaf/trace/shading/rect_light_shading.h"
#include "ltc_reference.h"

using namespace aaf;
using ltc_reference::Rectangle;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Form factor of a rectangle parallel to the tangent plane at height h,
/// spanning [0, a] x [0, b] from the point's foot (a textbook closed form,
/// e.g. Howell's catalogue, C-11).
double corner_rectangle_form_factor(double a, double b, double h) {
    const double x = a / h, y = b / h;
    return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
            y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
           (2 * kPi);
}

/// A rectangle facing down at height h over [x0, x1] x [y0, y1].
Rectangle overhead(double x0, double x1, double y0, double y1, double h) {
    return {{x0, y0, h}, {0, y1 - y0, 0}, {x1 - x0, 0, 0}};
}

}  // namespace

TEST_CASE("Lambert U: the horizon-clipped edge integral equals a converged quadrature over the light to 1e-4",
          "[ratio][polygon]") {
    struct Case {
        const char *what;
        Rectangle light;
    };
    const Case cases[] = {
        {"overhead", overhead(-0.5, 0.5, -0.5, 0.5, 2.0)},
        {"off to the side, tilted", ltc_reference::facing_square({1.0, 0.4, 0.7}, 1.5, 0.8)},
        {"near grazing", ltc_reference::facing_square({1.0, 0.0, 0.05}, 2.0, 0.5)},
        {"partly below the horizon", {{1.0, -0.5, -0.5}, {0, 0, 1.0}, {0, 1.0, 0}}},
        {"mostly below the horizon", {{1.0, -0.5, -0.9}, {0, 0, 1.0}, {0, 1.0, 0}}},
        {"large, tilted, across the horizon", {{-2.0, 1.0, -1.0}, {4.0, 0.5, 0}, {0, 0, 3.0}}},
        {"tiny (1 mm at 1 m)", ltc_reference::facing_square({0.3, 0.2, 1.0}, 1.0, 1e-3)},
        {"far (1 m at 1 km)", ltc_reference::facing_square({-0.4, 0.1, 1.0}, 1000.0, 1.0)},
        {"close (1 m at 2 cm)", ltc_reference::facing_square({0.1, 0.1, 1.0}, 0.02, 1.0)},
    };
    for (const Case &c : cases) {
        INFO(c.what);
        const double analytic = polygon_form_factor(c.light.polygon());
        const double quadrature = ltc_reference::form_factor_by_quadrature(c.light);
        REQUIRE(quadrature > 0);
        CHECK(std::fabs(analytic - quadrature) <= 1e-4 * quadrature);
    }
}

TEST_CASE(
    "Lambert U: a parallel rectangle matches the closed form, also where vertex directions are nearly "
    "opposite",
    "[ratio][polygon]") {
    for (double a_over_h : {0.1, 1.0, 10.0, 1e3, 1e6}) {
        INFO("a / h = " << a_over_h);
        const double h = 1e-3, a = a_over_h * h;
        // A point under the middle of one edge: that edge's two vertex
        // directions are nearly opposite when a >> h.
        const double analytic = polygon_form_factor(overhead(-a, a, 0, a, h).polygon());
        const double closed_form = 2 * corner_rectangle_form_factor(a, a, h);
        CHECK(std::fabs(analytic - closed_form) <= 1e-9);
        // Centred square: four corner rectangles.
        const double centred = polygon_form_factor(overhead(-a, a, -a, a, h).polygon());
        CHECK(std::fabs(centred - 4 * corner_rectangle_form_factor(a, a, h)) <= 1e-9);
    }
}

TEST_CASE("Lambert U: non-negative, zero below the horizon and behind the emitter", "[ratio][polygon]") {
    // Entirely below the tangent plane.
    CHECK(polygon_form_factor(Rectangle{{1.0, -0.5, -1.5}, {0, 0, 1.0}, {0, 1.0, 0}}.polygon()) == 0);
    // Touching the horizon from below.
    CHECK(polygon_form_factor(Rectangle{{1.0, -0.5, -1.0}, {0, 0, 1.0}, {0, 1.0, 0}}.polygon()) == 0);
    for (int k = 0; k < 50; ++k) {
        const double angle = k * 0.13;
        const Rectangle light = ltc_reference::facing_square(
            {std::cos(angle), std::sin(angle), std::sin(3 * angle)}, 1 + k * 0.1, 0.5 + 0.03 * k);
        const double u = polygon_form_factor(light.polygon());
        CHECK(u >= 0);
        CHECK(u <= 1);
    }
    // The world-space U of a light whose back faces the point is 0, of one
    // facing it the albedo times the radiance times the form factor.
    LightPlane plane = LightPlane::square({0, 2, 0}, {0, -1, 0}, 1.0f);
    const SurfaceReflectance lambert{{0.5f, 0.25f, 1.0f}, {0, 0, 0}, 0.5f};
    const UnshadowedLight lit =
        rect_light_unshadowed({plane, {2, 2, 2}}, {0, 0, 0}, {0, 1, 0}, {0, 1, 0}, lambert);
    const double ff = 4 * corner_rectangle_form_factor(0.5, 0.5, 2.0);
    CHECK(lit.diffuse.x == Approx(0.5 * 2 * ff).epsilon(1e-6));
    CHECK(lit.diffuse.y == Approx(0.25 * 2 * ff).epsilon(1e-6));
    plane.normal = {0, 1, 0};
    const UnshadowedLight behind =
        rect_light_unshadowed({plane, {2, 2, 2}}, {0, 0, 0}, {0, 1, 0}, {0, 1, 0}, lambert);
    CHECK(behind.total() == Vec3{0, 0, 0});
}
