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
}

}  // namespace aaf::trace
