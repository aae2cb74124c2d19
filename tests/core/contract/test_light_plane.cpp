#include <catch2/catch.hpp>

#include "aaf/core/contract/light_plane.h"
#include "aaf/core/util/error.h"

using aaf::LightPlane;
using aaf::Vec3;

TEST_CASE("Light-plane distance is measured along the light normal", "[light]") {
    const LightPlane light = LightPlane::square({0, 3, 0}, {0, -1, 0}, 1.0f);
    CHECK(light.plane_distance_m({5, 0, -7}) == Approx(3.0f));  // receiver on the ground
    CHECK(light.plane_distance_m({0.3f, 1.2f, 0.1f}) == Approx(1.8f));
}

TEST_CASE("In-plane distance excludes motion along the light normal (AAF Eq. 12)", "[light]") {
    const LightPlane down = LightPlane::square({0, 3, 0}, {0, -1, 0}, 1.0f);
    // delta = (-3, -4, 0): |delta|^2 = 25, (n . delta)^2 = 16 -> 9.
    CHECK(down.in_plane_distance_sq({1, 2, 3}, {4, 6, 3}) == Approx(9.0f));

    const LightPlane tilted = LightPlane::square({0, 0, 0}, normalize(Vec3{1, 1, 0}), 1.0f);
    // delta = (1, 0, 0): 1 - (1/sqrt 2)^2 = 0.5.
    CHECK(tilted.in_plane_distance_sq({1, 0, 0}, {0, 0, 0}) == Approx(0.5f));
    // Motion purely along the normal does not count.
    CHECK(tilted.in_plane_distance_sq({2, 2, 0}, {0, 0, 0}) == Approx(0.0f).margin(1e-6));
}

TEST_CASE("Square light uses sigma = side / 2 and an orthonormal frame", "[light]") {
    const LightPlane light = LightPlane::square({1, 2, 3}, {0, 0, -2}, 1.5f);
    CHECK(light.sigma_m == Approx(0.75f));
    CHECK_NOTHROW(light.validate());
    CHECK(aaf::dot(light.axis_u, light.normal) == Approx(0.0f).margin(1e-6));
    CHECK(aaf::length(aaf::cross(light.axis_u, light.axis_v)) == Approx(1.0f));

    LightPlane broken = light;
    broken.axis_u = light.normal;
    CHECK_THROWS_AS(broken.validate(), aaf::Error);
    broken = light;
    broken.sigma_m = 0;
    CHECK_THROWS_AS(broken.validate(), aaf::Error);
}
