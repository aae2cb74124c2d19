#include <cmath>
#include <vector>

#include "scene_description.h"

namespace aaf::trace {

SceneDescription make_tentacles_scene(int width, int height) {
    SceneDescription scene;
    scene.name = "tentacles";

    auto ground_height = [](float x, float z) { return 0.06f * std::sin(2.5f * x) * std::cos(2.0f * z); };
    Mesh ground;
    ground.object_id = 1;
    ground.albedo = {0.72f, 0.72f, 0.75f};
    ground.add_heightfield(5.0f, 160, ground_height);
    scene.meshes.push_back(ground);

    // Thin tapering tubes that rise from the ground and curl over it.
    constexpr int kTentacles = 7;
    constexpr int kPoints = 48;
    for (int k = 0; k < kTentacles; ++k) {
        const float angle = 2.0f * 3.14159265f * float(k) / float(kTentacles);
        const float base_x = 0.9f * std::cos(angle), base_z = 0.9f * std::sin(angle);
        std::vector<Vec3> centre;
        std::vector<float> radius;
        for (int i = 0; i < kPoints; ++i) {
            const float t = float(i) / float(kPoints - 1);
            const float swirl = angle + 2.2f * t;
            const float reach = 0.9f + 0.5f * std::sin(3.0f * t + float(k));
            centre.push_back({reach * std::cos(swirl) * (0.4f + t), ground_height(base_x, base_z) + 1.5f * t,
                              reach * std::sin(swirl) * (0.4f + t)});
            radius.push_back(0.05f * (1.0f - t) + 0.012f);
        }
        Mesh tentacle;
        tentacle.object_id = 2 + k;
        tentacle.albedo = {0.55f + 0.05f * float(k % 3), 0.35f, 0.45f};
        tentacle.add_tube(centre, radius, 10);
        scene.meshes.push_back(tentacle);
    }

    scene.light = LightPlane::square({0, 3.0f, 0}, {0, -1, 0}, 1.0f);
    scene.light_intensity = 30.0f;
    scene.camera = PinholeCamera::look_at({0, 4.0f, 5.0f}, {0, 0.4f, 0}, {0, 1, 0}, 45.0f, width, height);
    return scene;
}

}  // namespace aaf::trace
