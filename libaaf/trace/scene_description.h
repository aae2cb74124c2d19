#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "aaf/core/contract/light_plane.h"
#include "camera.h"

namespace aaf::trace {

/// A surface's reflectance: Lambertian albedo plus an optional GGX
/// (Trowbridge-Reitz) specular lobe with Schlick Fresnel.
struct Material {
    Vec3 albedo{0.75f, 0.75f, 0.75f};  ///< diffuse reflectance per channel, [0, 1]
    Vec3 specular{0, 0, 0};            ///< Fresnel reflectance at normal incidence (F0); 0 = none
    float roughness = 0.5f;            ///< GGX alpha = roughness^2
    /// ISG's glossiness (Sec. 3.2, Fig. 4): the half-angle of the cone around
    /// the mirror direction outside which the glossy reflection is zero,
    /// written to the isg AOVs; 0 = not glossy. The beauty does not use it.
    float theta_max_deg = 0;
    /// Procedural albedo texture: a 3D checker of cubes `checker_size_m` on a
    /// side in world space, alternating `albedo` and `checker_albedo`; 0 = none.
    float checker_size_m = 0;
    Vec3 checker_albedo{0.2f, 0.2f, 0.2f};
    /// Procedural normal map: the shading normal tilts by the tangential part
    /// of the gradient of bump_slope * (period / 2 pi) * (sin kx + sin ky + sin kz),
    /// k = 2 pi / bump_period_m (world space); a slope of 0 = none.
    float bump_slope = 0;
    float bump_period_m = 0.1f;

    bool has_specular() const { return specular.x > 0 || specular.y > 0 || specular.z > 0; }
};

/// An affine map applied to object-space points: scale, then rotate, then translate.
struct Transform {
    float m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  ///< rotation times scale
    Vec3 translation;

    Vec3 apply(Vec3 p) const {
        return Vec3{m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z,
                    m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
                    m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z} +
               translation;
    }
    /// Euler rotation in degrees about x, then y, then z, after scaling by `scale`.
    static Transform from(Vec3 scale, Vec3 rotate_deg, Vec3 translate);
};

/// A triangle mesh with one material, identified in the object-id AOV.
struct Mesh {
    std::vector<Vec3> positions;         ///< world metres
    std::vector<std::uint32_t> indices;  ///< three per triangle
    int object_id = 1;                   ///< > 0; 0 is the background
    Material material;
    /// Translation applied to `positions` by the animation (set_frame()), and
    /// its change since the previous frame (for motion vectors), metres.
    Vec3 offset_m{0, 0, 0};
    Vec3 moved_since_previous_frame_m{0, 0, 0};

    std::size_t triangle_count() const { return indices.size() / 3; }

    /// Appends the axis-aligned box [lo, hi] mapped by `to_world`.
    void add_box(Vec3 lo, Vec3 hi, const Transform &to_world);
    /// Appends a quad (two triangles) with corners a, b, c, d in order.
    void add_quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d);
    /// Appends a UV sphere of `segments` longitudes and segments/2 latitudes.
    void add_sphere(Vec3 center, float radius_m, int segments, const Transform &to_world);
    /// Appends a closed cylinder around the y axis from y = 0 to `height_m`.
    void add_cylinder(float radius_m, float height_m, int segments, const Transform &to_world);
};

/// A planar rectangular area light (AAF Fig. 2) with its emission.
struct SceneLight {
    LightPlane plane;
    float intensity = 1.0f;  ///< radiant intensity along the light normal, W/sr
    Vec3 color{1, 1, 1};     ///< multiplies the intensity per channel
};

/// Keyframed values of the camera and lights (linear interpolation between
/// keys, held constant before the first and after the last key).
struct CameraKey {
    double frame = 1;
    Vec3 eye, target;
    float fov_y_deg = 45;
    float focus_distance_m = 1;
};
struct LightKey {
    double frame = 1;
    Vec3 center;
    float intensity = 1;
};
/// An object's translation from where the scene file puts it.
struct ObjectKey {
    double frame = 1;
    Vec3 offset_m;
};
struct Animation {
    std::vector<CameraKey> camera;               ///< empty = static camera
    std::vector<std::vector<LightKey>> lights;   ///< per light; empty = static
    std::vector<std::vector<ObjectKey>> meshes;  ///< per mesh (its object's track); empty = static
    Vec3 camera_up{0, 1, 0};
};

/// Everything the tracer needs to render one frame.
struct SceneDescription {
    std::string name;
    std::string source;  ///< the scene file it was read from
    std::vector<Mesh> meshes;
    /// lights[0] is the key light: the AAF AOVs (visibility, d1, d2,
    /// unshadowed) describe it; the beauty sums every light.
    std::vector<SceneLight> lights;
    Camera camera;
    Animation animation;

    const LightPlane &key_light() const { return lights.front().plane; }
    /// The camera at `frame` (the static camera when it has no keys).
    Camera camera_at(double frame) const;
    /// Moves the camera, lights and objects to `frame`.
    void set_frame(double frame);
};

}  // namespace aaf::trace
