#include "scene_hash.h"

#include <cstdio>

namespace aaf::trace {

void Fnv1a::add_bytes(const void *data, std::size_t size) {
    const auto *bytes = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < size; ++i) {
        state_ ^= bytes[i];
        state_ *= 0x100000001b3ull;  // the FNV 64-bit prime
    }
}

std::uint64_t scene_hash(const SceneDescription &scene, const RenderSettings &settings) {
    Fnv1a h;
    h.add(std::int64_t(settings.width));
    h.add(std::int64_t(settings.height));
    h.add(std::int64_t(settings.seed));
    h.add(settings.frame);
    h.add(std::int64_t(settings.cosine_falloff));
    if (settings.skip_self_occluded) h.add(std::int64_t(1));  // renders without it keep their earlier hash

    const Camera &camera = scene.camera;
    for (Vec3 v : {camera.eye, camera.forward, camera.right, camera.up}) h.add(v);
    h.add(camera.tan_half_fov_y);
    h.add(camera.aperture_radius_m);
    h.add(camera.focus_distance_m);

    h.add(std::int64_t(scene.meshes.size()));
    for (const Mesh &mesh : scene.meshes) {
        h.add(std::int64_t(mesh.object_id));
        h.add(mesh.material.albedo);
        h.add(mesh.material.specular);
        h.add(mesh.material.roughness);
        // Hashed only when set, so scenes from before it keep their hashes (and resume).
        if (mesh.material.theta_max_deg > 0) h.add(mesh.material.theta_max_deg);
        if (mesh.material.checker_size_m > 0) {
            h.add(mesh.material.checker_size_m);
            h.add(mesh.material.checker_albedo);
        }
        if (mesh.material.bump_slope > 0) {
            h.add(mesh.material.bump_slope);
            h.add(mesh.material.bump_period_m);
        }
        h.add(std::int64_t(mesh.positions.size()));
        for (Vec3 p : mesh.positions) h.add(p);
        // The motion vectors' share of an animated object (only when it moves).
        const Vec3 moved = mesh.moved_since_previous_frame_m;
        if (moved.x != 0 || moved.y != 0 || moved.z != 0) h.add(moved);
        h.add(std::int64_t(mesh.indices.size()));
        h.add_bytes(mesh.indices.data(), mesh.indices.size() * sizeof(mesh.indices[0]));
    }

    h.add(std::int64_t(scene.lights.size()));
    for (const SceneLight &light : scene.lights) {
        const LightPlane &plane = light.plane;
        for (Vec3 v : {plane.center, plane.normal, plane.axis_u, plane.axis_v}) h.add(v);
        h.add(plane.width_m);
        h.add(plane.height_m);
        h.add(plane.sigma_m);
        h.add(std::int64_t(plane.profile));
        h.add(light.intensity);
        h.add(light.color);
    }
    return h.value();
}

std::string hash_to_hex(std::uint64_t hash) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
    return text;
}

}  // namespace aaf::trace
