#include <cmath>

#include "scene_description.h"

namespace aaf::trace {

namespace {

/// A square lattice: bars along x and along z crossing at one height.
Mesh make_lattice(float height_m, float angle_deg, int object_id, Vec3 albedo) {
    constexpr float kHalfExtent = 1.2f;  // metres
    constexpr float kSpacing = 0.3f;
    constexpr float kBarWidth = 0.05f;
    constexpr float kBarThickness = 0.03f;
    Mesh mesh;
    mesh.object_id = object_id;
    mesh.albedo = albedo;
    const float angle = angle_deg * 3.14159265358979f / 180.0f;
    const float y0 = height_m - 0.5f * kBarThickness, y1 = height_m + 0.5f * kBarThickness;
    const int bars = int(std::round(2 * kHalfExtent / kSpacing)) + 1;
    for (int i = 0; i < bars; ++i) {
        const float offset = -kHalfExtent + i * kSpacing;
        mesh.add_box({-kHalfExtent, y0, offset - 0.5f * kBarWidth},
                     {kHalfExtent, y1, offset + 0.5f * kBarWidth}, angle);
        mesh.add_box({offset - 0.5f * kBarWidth, y0, -kHalfExtent},
                     {offset + 0.5f * kBarWidth, y1, kHalfExtent}, angle);
    }
    return mesh;
}

}  // namespace

SceneDescription make_grids_scene(int width, int height) {
    SceneDescription scene;
    scene.name = "grids";

    // The ground reaches past the top of the frame (about 11 m behind the origin).
    scene.meshes.push_back(ground_plane(24.0f, 1, {0.75f, 0.75f, 0.75f}));
    scene.meshes.push_back(make_lattice(0.35f, 0.0f, 2, {0.80f, 0.30f, 0.25f}));
    scene.meshes.push_back(make_lattice(0.80f, 20.0f, 3, {0.30f, 0.70f, 0.30f}));
    scene.meshes.push_back(make_lattice(1.30f, 40.0f, 4, {0.30f, 0.40f, 0.85f}));

    // A 1 m square light 3 m above the ground; sigma = side / 2 (light_plane.h).
    scene.light = LightPlane::square({0, 3.0f, 0}, {0, -1, 0}, 1.0f);
    // Ground under the light: albedo/pi * I / 3^2 = 0.75/pi * 30/9 ~ 0.8.
    scene.light_intensity = 30.0f;
    scene.camera = PinholeCamera::look_at({0, 4.2f, 5.2f}, {0, 0.2f, 0}, {0, 1, 0}, 45.0f, width, height);
    return scene;
}

}  // namespace aaf::trace
