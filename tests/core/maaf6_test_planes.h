// Shared by the MAAF 6D tests: an example wedge and the planes
// maaf6_filter_layer() reads, with the views of them it takes.
#pragma once

#include <array>
#include <vector>

#include "aaf/core/maaf6.h"
#include "aaf/core/maaf6_filter.h"

namespace aaf::maaf6_test {

/// y-wedge [1, 2] with Omega_y^max 10 and a u-wedge of slopes [u_min, u_max] (Omega_u^max 100).
inline Maaf6Wedge example_wedge(double u_min, double u_max) {
    Maaf6Wedge w;
    w.has_y = true;
    w.y_min = 1;
    w.y_max = 2;
    w.omega_y_max = 10;
    w.has_u = true;
    w.u_min = u_min;
    w.u_max = u_max;
    w.omega_u_max = 100;
    w.omega_x_max = 1e6;
    return w;
}

/// The planes maaf6_filter_layer() reads, all width x height, and the views of them it takes.
struct Maaf6Planes {
    int width = 0, height = 0;
    std::vector<std::vector<float>> sums, weights;  ///< 3 (2N-1)^2 and (2N-1)^2 of them
    std::vector<float> y_min, y_max, u_min, u_max, omega_x, id, pixel_size, spp, position[3], normal[3];

    Maaf6LayerInputs layer(double omega_y_max) const {
        Maaf6LayerInputs in;
        for (const auto &p : sums) in.sums.push_back(view(p));
        for (const auto &p : weights) in.weights.push_back(view(p));
        in.y_min = view(y_min);
        in.y_max = view(y_max);
        in.omega_y_max = omega_y_max;
        return in;
    }
    Maaf6SharedInputs shared(double omega_u_max) const {
        Maaf6SharedInputs in;
        in.u_min = view(u_min);
        in.u_max = view(u_max);
        in.omega_x = view(omega_x);
        for (std::size_t c = 0; c < 3; ++c) {
            in.position[c] = view(position[c]);
            in.normal[c] = view(normal[c]);
        }
        in.object_id = view(id);
        in.pixel_size = view(pixel_size);
        in.samples = view(spp);
        in.omega_u_max = omega_u_max;
        return in;
    }

  private:
    ConstPlaneView view(const std::vector<float> &plane) const {
        return plane_view<const float>(plane.data(), width, height);
    }
};

/// Runs maaf6_filter_layer() on `planes` into `out` (R, G, B planes of the planes' size), with a
/// light whose axis_u is +x and axis_v +z (a floor's t1 = +x, t2 = -z).
inline void filter_planes(const Maaf6Planes &planes, double omega_y_max, double omega_u_max,
                          const Maaf6FilterParams &params, std::vector<float> (&out)[3]) {
    LightPlane light;
    light.axis_u = {1, 0, 0};
    light.axis_v = {0, 0, 1};
    for (auto &o : out) o.assign(std::size_t(planes.width) * std::size_t(planes.height), -1.0f);
    maaf6_filter_layer(planes.layer(omega_y_max), planes.shared(omega_u_max), light, params,
                       {plane_view(out[0].data(), planes.width, planes.height),
                        plane_view(out[1].data(), planes.width, planes.height),
                        plane_view(out[2].data(), planes.width, planes.height)});
}

}  // namespace aaf::maaf6_test
