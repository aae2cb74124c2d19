// EmbreeScene::intersect takes the triangle from Embree and computes the hit
// itself: its distance and normal must be Embree's up to float rounding, on
// every instruction set Embree may use.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "aaf/core/util/instruction_set.h"
#include "embree_scene.h"

using namespace aaf;
using namespace aaf::trace;

namespace {

SceneDescription spheres_and_boxes() {
    SceneDescription scene;
    Mesh ground;
    ground.add_quad({-5, 0, -5}, {5, 0, -5}, {5, 0, 5}, {-5, 0, 5});
    scene.meshes.push_back(ground);
    Mesh sphere;
    sphere.add_sphere({0.5f, 1, 0.2f}, 0.7f, 24, Transform{});
    scene.meshes.push_back(sphere);
    Mesh box;
    box.add_box({-1.5f, 0, -1}, {-0.5f, 1.2f, 0.3f}, Transform::from({1, 1, 1}, {10, 35, 5}, {0, 0.1f, 0}));
    scene.meshes.push_back(box);
    return scene;
}

/// Embree's own closest hit of the ray, as rtcIntersect1 reports it.
RTCRayHit embree_hit(const EmbreeScene &bvh, Vec3 origin, Vec3 direction) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query{};
    query.ray.org_x = origin.x;
    query.ray.org_y = origin.y;
    query.ray.org_z = origin.z;
    query.ray.dir_x = direction.x;
    query.ray.dir_y = direction.y;
    query.ray.dir_z = direction.z;
    query.ray.tfar = std::numeric_limits<float>::infinity();
    query.ray.mask = std::numeric_limits<unsigned>::max();
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(bvh.handle(), &context, &query);
    return query;
}

}  // namespace

TEST_CASE("A hit's distance and normal are Embree's up to rounding, under every instruction set",
          "[trace][isa]") {
    const InstructionSet before = instruction_set();
    for (InstructionSet set : kInstructionSets) {
        if (!cpu_supports(set)) continue;
        set_instruction_set(set);
        const EmbreeScene bvh(spheres_and_boxes(), false);
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
        int hits = 0;
        for (int k = 0; k < 4000; ++k) {
            const Vec3 origin{3 * unit(rng), 1.5f + unit(rng), 3 * unit(rng)};
            const Vec3 target{unit(rng), 0.6f + 0.6f * unit(rng), unit(rng)};
            const Vec3 direction = target - origin;
            const Hit hit = bvh.intersect(origin, direction, 0.0f, std::numeric_limits<float>::infinity());
            const RTCRayHit expected = embree_hit(bvh, origin, direction);
            INFO("instruction set " << instruction_set_name(set) << ", ray " << k);
            REQUIRE(hit.found == (expected.hit.geomID != RTC_INVALID_GEOMETRY_ID));
            if (!hit.found) continue;
            ++hits;
            REQUIRE(hit.mesh_index == expected.hit.geomID);
            CHECK(std::abs(hit.distance - expected.ray.tfar) <= 1e-5f * expected.ray.tfar);
            const Vec3 embree_normal{expected.hit.Ng_x, expected.hit.Ng_y, expected.hit.Ng_z};
            // Same orientation and direction: the normals' angle is below ~1e-3 rad.
            CHECK(dot(normalize(hit.geometric_normal), normalize(embree_normal)) > 1 - 1e-6f);
        }
        CHECK(hits > 2000);
    }
    set_instruction_set(before);
}
