#include <cmath>

#include "scene_description.h"

namespace aaf::trace {

SceneDescription make_spheres_scene(int width, int height) {
    SceneDescription scene;
    scene.name = "spheres";

    // A curved receiver: a shallow bowl rising towards its rim.
    Mesh receiver;
    receiver.object_id = 1;
    receiver.albedo = {0.75f, 0.72f, 0.68f};
    receiver.add_heightfield(4.0f, 128, [](float x, float z) { return 0.06f * (x * x + z * z); });
    scene.meshes.push_back(receiver);

    struct Ball {
        Vec3 center;
        float radius_m;
        Vec3 albedo;
    };
    const Ball balls[] = {
        {{-0.9f, 0.75f, 0.2f}, 0.30f, {0.85f, 0.35f, 0.30f}},
        {{0.1f, 1.25f, -0.3f}, 0.35f, {0.30f, 0.70f, 0.35f}},
        {{0.9f, 0.55f, 0.4f}, 0.22f, {0.30f, 0.45f, 0.85f}},
        {{0.3f, 0.35f, 0.9f}, 0.18f, {0.85f, 0.75f, 0.30f}},
        {{-0.4f, 1.70f, -0.9f}, 0.28f, {0.70f, 0.40f, 0.80f}},
    };
    int id = 2;
    for (const Ball &ball : balls) {
        Mesh sphere;
        sphere.object_id = id++;
        sphere.albedo = ball.albedo;
        sphere.add_sphere(ball.center, ball.radius_m, 48);
        scene.meshes.push_back(sphere);
    }

    scene.light = LightPlane::square({0, 3.2f, 0}, {0, -1, 0}, 1.2f);
    scene.light_intensity = 36.0f;  // rim ~ albedo/pi * I / 3.2^2 ~ 0.8 under the light
    scene.camera = PinholeCamera::look_at({0, 3.6f, 4.8f}, {0, 0.4f, 0}, {0, 1, 0}, 45.0f, width, height);
    return scene;
}

}  // namespace aaf::trace
