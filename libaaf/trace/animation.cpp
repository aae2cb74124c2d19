#include <algorithm>

#include "scene_description.h"

namespace aaf::trace {

namespace {

Vec3 lerp(Vec3 a, Vec3 b, float t) {
    return a + (b - a) * t;
}
float lerp(float a, float b, float t) {
    return a + (b - a) * t;
}

/// The value of `keys` (sorted by frame, not empty) at `frame`: linear between
/// the two keys around it, held before the first and after the last.
template <typename Key, typename Mix>
Key sample(const std::vector<Key> &keys, double frame, const Mix &mix) {
    if (frame <= keys.front().frame) return keys.front();
    if (frame >= keys.back().frame) return keys.back();
    const auto after = std::upper_bound(keys.begin(), keys.end(), frame,
                                        [](double f, const Key &key) { return f < key.frame; });
    const Key &a = *(after - 1), &b = *after;
    return mix(a, b, float((frame - a.frame) / (b.frame - a.frame)));
}

}  // namespace

Camera SceneDescription::camera_at(double frame) const {
    if (animation.camera.empty()) return camera;
    const CameraKey key =
        sample(animation.camera, frame, [](const CameraKey &a, const CameraKey &b, float t) {
            CameraKey mixed;
            mixed.eye = lerp(a.eye, b.eye, t);
            mixed.target = lerp(a.target, b.target, t);
            mixed.fov_y_deg = lerp(a.fov_y_deg, b.fov_y_deg, t);
            mixed.focus_distance_m = lerp(a.focus_distance_m, b.focus_distance_m, t);
            return mixed;
        });
    Camera moved =
        Camera::look_at(key.eye, key.target, animation.camera_up, key.fov_y_deg, camera.width, camera.height);
    moved.aperture_radius_m = camera.aperture_radius_m;
    moved.focus_distance_m = key.focus_distance_m;
    return moved;
}

void SceneDescription::set_frame(double frame) {
    camera = camera_at(frame);
    for (std::size_t i = 0; i < lights.size() && i < animation.lights.size(); ++i) {
        if (animation.lights[i].empty()) continue;
        const LightKey key =
            sample(animation.lights[i], frame, [](const LightKey &a, const LightKey &b, float t) {
                LightKey mixed;
                mixed.center = lerp(a.center, b.center, t);
                mixed.intensity = lerp(a.intensity, b.intensity, t);
                return mixed;
            });
        lights[i].plane.center = key.center;
        lights[i].intensity = key.intensity;
    }
    for (std::size_t i = 0; i < meshes.size() && i < animation.meshes.size(); ++i) {
        const std::vector<ObjectKey> &keys = animation.meshes[i];
        if (keys.empty()) continue;
        const auto offset_at = [&keys](double at) {
            return sample(keys, at,
                          [](const ObjectKey &a, const ObjectKey &b, float t) {
                              ObjectKey mixed;
                              mixed.offset_m = lerp(a.offset_m, b.offset_m, t);
                              return mixed;
                          })
                .offset_m;
        };
        Mesh &mesh = meshes[i];
        const Vec3 offset = offset_at(frame);
        const Vec3 shift = offset - mesh.offset_m;
        for (Vec3 &position : mesh.positions) position = position + shift;
        mesh.offset_m = offset;
        mesh.moved_since_previous_frame_m = offset - offset_at(frame - 1);
    }
}

}  // namespace aaf::trace
