#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "aaf/core/light_plane.h"
#include "camera.h"

namespace aaf::trace {

/// A triangle mesh with one diffuse material, identified in the object-id AOV.
struct Mesh {
    std::vector<Vec3> positions;         ///< world metres
    std::vector<std::uint32_t> indices;  ///< three per triangle
    int object_id = 1;                   ///< > 0; 0 is the background
    Vec3 albedo{0.75f, 0.75f, 0.75f};    ///< diffuse reflectance per channel

    /// Appends an axis-aligned box [lo, hi] transformed by a rotation of
    /// `angle_rad` about the vertical (y) axis.
    void add_box(Vec3 lo, Vec3 hi, float angle_rad);
    /// Appends a quad (two triangles) with corners a, b, c, d in order.
    void add_quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d);
    /// Appends a UV sphere of `segments` longitudes and segments/2 latitudes.
    void add_sphere(Vec3 center, float radius_m, int segments);
    /// Appends the surface y = height(x, z) over [-half, half]^2 on a
    /// `resolution` x `resolution` grid of quads.
    template <typename HeightFn>
    void add_heightfield(float half_extent_m, int resolution, const HeightFn &height);
    /// Appends a tube of `sides` sides around the polyline `centre`, with a
    /// radius per polyline point; ends are left open.
    void add_tube(const std::vector<Vec3> &centre, const std::vector<float> &radius_m, int sides);
};

template <typename HeightFn>
void Mesh::add_heightfield(float half_extent_m, int resolution, const HeightFn &height) {
    const auto base = std::uint32_t(positions.size());
    for (int j = 0; j <= resolution; ++j)
        for (int i = 0; i <= resolution; ++i) {
            const float x = -half_extent_m + 2 * half_extent_m * float(i) / float(resolution);
            const float z = -half_extent_m + 2 * half_extent_m * float(j) / float(resolution);
            positions.push_back({x, height(x, z), z});
        }
    const auto stride = std::uint32_t(resolution + 1);
    for (int j = 0; j < resolution; ++j)
        for (int i = 0; i < resolution; ++i) {
            const std::uint32_t a = base + std::uint32_t(j) * stride + std::uint32_t(i);
            indices.insert(indices.end(), {a, a + stride, a + stride + 1, a, a + stride + 1, a + 1});
        }
}

/// A flat square ground at y = 0, centred on the origin.
Mesh ground_plane(float half_extent_m, int object_id, Vec3 albedo);

/// Everything the tracer needs to render one frame.
struct SceneDescription {
    std::string name;
    std::vector<Mesh> meshes;
    LightPlane light;
    float light_intensity = 1.0f;  ///< radiant intensity along the light normal, W/sr
    PinholeCamera camera;
};

/// The built-in `grids` scene (after AAF Fig. 6): a ground plane under three
/// square lattices of thin bars at different heights and rotations, lit by a
/// square Gaussian area light above.
SceneDescription make_grids_scene(int width, int height);
/// `spheres` (after AAF Fig. 8): spheres floating above a curved receiver.
SceneDescription make_spheres_scene(int width, int height);
/// `tentacles` (after AAF Fig. 9): thin curved occluders over a wavy ground.
SceneDescription make_tentacles_scene(int width, int height);
/// `bench` (after AAF Fig. 1): a slatted bench of many thin parts, contact shadows.
SceneDescription make_bench_scene(int width, int height);

/// The built-in scene called `name`; throws aaf::Error listing the known ones.
SceneDescription make_builtin_scene(const std::string &name, int width, int height);

}  // namespace aaf::trace
