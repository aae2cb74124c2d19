#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "aaf/core/light_plane.h"
#include "camera.h"

namespace aaf::trace {

/// A triangle mesh with one diffuse material, identified in the object-id AOV.
struct Mesh {
    std::vector<Vec3> positions;               ///< world metres
    std::vector<std::uint32_t> indices;        ///< three per triangle
    int object_id = 1;                         ///< > 0; 0 is the background
    Vec3 albedo{0.75f, 0.75f, 0.75f};          ///< diffuse reflectance per channel

    /// Appends an axis-aligned box [lo, hi] transformed by a rotation of
    /// `angle_rad` about the vertical (y) axis.
    void add_box(Vec3 lo, Vec3 hi, float angle_rad);
    /// Appends a quad (two triangles) with corners a, b, c, d in order.
    void add_quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d);
};

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

}  // namespace aaf::trace
