#pragma once

#include <cmath>

#include "aaf/core/math/vec3.h"

namespace aaf::trace {

/// A pinhole or thin-lens camera. Pixel (px, py) covers [px, px+1] x [py, py+1]
/// in raster space, y down; `ray_direction` takes continuous raster coordinates.
struct Camera {
    Vec3 eye;                  ///< world metres; the lens centre
    Vec3 forward, right, up;   ///< orthonormal; right and up span the image plane
    float tan_half_fov_y = 0;  ///< tan of half the vertical field of view
    int width = 0, height = 0;
    /// Thin lens: radius of the aperture disc (0 = pinhole) and the distance
    /// along `forward` of the plane in focus, both in world metres.
    float aperture_radius_m = 0;
    float focus_distance_m = 1;

    static Camera look_at(Vec3 eye, Vec3 target, Vec3 up_hint, float fov_y_deg, int width, int height) {
        Camera camera;
        camera.eye = eye;
        camera.forward = normalize(target - eye);
        camera.right = normalize(cross(camera.forward, up_hint));
        camera.up = cross(camera.right, camera.forward);
        camera.tan_half_fov_y = std::tan(0.5f * fov_y_deg * 3.14159265358979f / 180.0f);
        camera.width = width;
        camera.height = height;
        return camera;
    }

    bool is_thin_lens() const { return aperture_radius_m > 0; }

    /// Unnormalised direction of the central (pinhole) ray through raster
    /// point (x, y); its component along `forward` is 1.
    Vec3 ray_direction(float x, float y) const {
        const float aspect = float(width) / float(height);
        const float ndc_x = (2.0f * x / float(width) - 1.0f) * aspect * tan_half_fov_y;
        const float ndc_y = (1.0f - 2.0f * y / float(height)) * tan_half_fov_y;
        return forward + right * ndc_x + up * ndc_y;
    }

    /// Continuous raster coordinates of world point `p` as the pinhole sees it
    /// (for motion vectors); false when `p` lies behind the camera.
    bool raster_of(Vec3 p, float &x, float &y) const {
        const Vec3 d = p - eye;
        const float depth = dot(d, forward);
        if (depth <= 0) return false;
        const float aspect = float(width) / float(height);
        const float ndc_x = dot(d, right) / depth / (aspect * tan_half_fov_y);
        const float ndc_y = dot(d, up) / depth / tan_half_fov_y;
        x = 0.5f * (ndc_x + 1.0f) * float(width);
        y = 0.5f * (1.0f - ndc_y) * float(height);
        return true;
    }
};

}  // namespace aaf::trace
