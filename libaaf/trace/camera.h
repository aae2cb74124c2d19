#pragma once

#include <cmath>

#include "aaf/core/vec3.h"

namespace aaf::trace {

/// A pinhole camera. Pixel (px, py) covers [px, px+1] x [py, py+1] in raster
/// space, y down; `ray_direction` takes continuous raster coordinates.
struct PinholeCamera {
    Vec3 eye;
    Vec3 forward, right, up;   ///< orthonormal; right and up span the image plane
    float tan_half_fov_y = 0;  ///< tan of half the vertical field of view
    int width = 0, height = 0;

    static PinholeCamera look_at(Vec3 eye, Vec3 target, Vec3 up_hint, float fov_y_deg, int width,
                                 int height) {
        PinholeCamera camera;
        camera.eye = eye;
        camera.forward = normalize(target - eye);
        camera.right = normalize(cross(camera.forward, up_hint));
        camera.up = cross(camera.right, camera.forward);
        camera.tan_half_fov_y = std::tan(0.5f * fov_y_deg * 3.14159265358979f / 180.0f);
        camera.width = width;
        camera.height = height;
        return camera;
    }

    /// Unnormalised direction through raster point (x, y).
    Vec3 ray_direction(float x, float y) const {
        const float aspect = float(width) / float(height);
        const float ndc_x = (2.0f * x / float(width) - 1.0f) * aspect * tan_half_fov_y;
        const float ndc_y = (1.0f - 2.0f * y / float(height)) * tan_half_fov_y;
        return forward + right * ndc_x + up * ndc_y;
    }
};

}  // namespace aaf::trace
