#include <cmath>

#include "scene_description.h"

namespace aaf::trace {

SceneDescription make_bench_scene(int width, int height) {
    SceneDescription scene;
    scene.name = "bench";

    scene.meshes.push_back(ground_plane(8.0f, 1, {0.70f, 0.70f, 0.68f}));

    // Seat and backrest slats (thin boards with gaps), legs down to the ground.
    const float angle = 25.0f * 3.14159265f / 180.0f;
    constexpr float kHalfLength = 0.9f, kSlatDepth = 0.06f, kGap = 0.025f, kThickness = 0.03f;
    Mesh slats;
    slats.object_id = 2;
    slats.albedo = {0.62f, 0.42f, 0.25f};
    for (int i = 0; i < 6; ++i) {  // seat at 0.45 m
        const float z0 = -0.25f + i * (kSlatDepth + kGap);
        slats.add_box({-kHalfLength, 0.45f, z0}, {kHalfLength, 0.45f + kThickness, z0 + kSlatDepth}, angle);
    }
    for (int i = 0; i < 4; ++i) {  // backrest: vertical boards stacked upwards
        const float y0 = 0.60f + i * (kSlatDepth + kGap);
        slats.add_box({-kHalfLength, y0, -0.30f}, {kHalfLength, y0 + kSlatDepth, -0.30f + kThickness}, angle);
    }
    scene.meshes.push_back(slats);

    Mesh frame;
    frame.object_id = 3;
    frame.albedo = {0.25f, 0.25f, 0.28f};
    for (float x : {-0.75f, 0.75f}) {
        frame.add_box({x - 0.03f, 0.0f, 0.16f}, {x + 0.03f, 0.45f, 0.22f}, angle);    // front leg
        frame.add_box({x - 0.03f, 0.0f, -0.30f}, {x + 0.03f, 0.95f, -0.24f}, angle);  // back leg and post
        frame.add_box({x - 0.03f, 0.40f, -0.30f}, {x + 0.03f, 0.45f, 0.22f}, angle);  // seat rail
    }
    scene.meshes.push_back(frame);

    scene.light = LightPlane::square({0.4f, 2.8f, 0.6f}, {0, -1, 0}, 0.8f);
    scene.light_intensity = 26.0f;
    scene.camera = PinholeCamera::look_at({0.3f, 2.2f, 3.2f}, {0, 0.35f, 0}, {0, 1, 0}, 45.0f, width, height);
    return scene;
}

}  // namespace aaf::trace
