// Shared by the MAAF 6D tests: an example wedge and the planes
// maaf6_filter_layer() reads, with the views of them it takes.
#pragma once

#include <array>
#include <random>
#include <vector>

#include "aaf/core/methods/maaf6/maaf6_components.h"
#include "aaf/core/methods/maaf6/maaf6_filter.h"

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
    /// Optional (empty: none): the wedge's extremes over a temporal window.
    std::vector<float> window_y_min, window_y_max, window_u_min, window_u_max;
    SampleDensity y_density, lens_density;  ///< what y and u were drawn from (fitted pair weights)

    Maaf6LayerInputs layer(double omega_y_max) const {
        Maaf6LayerInputs in;
        for (const auto &p : sums) in.sums.push_back(view(p));
        for (const auto &p : weights) in.weights.push_back(view(p));
        in.y_min = view(y_min);
        in.y_max = view(y_max);
        if (!window_y_min.empty()) {
            in.window_y_min = view(window_y_min);
            in.window_y_max = view(window_y_max);
        }
        in.omega_y_max = omega_y_max;
        in.y_density = y_density;
        return in;
    }
    Maaf6SharedInputs shared(double omega_u_max) const {
        Maaf6SharedInputs in;
        in.u_min = view(u_min);
        in.u_max = view(u_max);
        if (!window_u_min.empty()) {
            in.window_u_min = view(window_u_min);
            in.window_u_max = view(window_u_max);
        }
        in.omega_x = view(omega_x);
        for (std::size_t c = 0; c < 3; ++c) {
            in.position[c] = view(position[c]);
            in.normal[c] = view(normal[c]);
        }
        in.object_id = view(id);
        in.pixel_size = view(pixel_size);
        in.samples = view(spp);
        in.omega_u_max = omega_u_max;
        in.lens_density = lens_density;
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

/// A floor of `width` x `height` pixels of `pixel_m` metres (normal +y) under a
/// lens-only wedge of slope s_u (both slopes, Omega_u^max 10), whose
/// unoccluded light is a checkerboard of 0.5 and 1.5 (mean 1): per pixel 16
/// lens samples (points uniform on [-0.1, 0.1] from `seed`), every other one
/// occluded, of radiance colour[c] times the unoccluded light, accumulated
/// for N = 3 and then scaled to `spp` samples (as `spp` / 16 repeats of them).
inline Maaf6Planes lens_checkerboard(int width, int height, double pixel_m, double s_u, float spp,
                                     unsigned seed, const float (&colour)[3]) {
    const std::size_t n = std::size_t(width) * std::size_t(height);
    Maaf6Planes planes;
    planes.width = width;
    planes.height = height;
    planes.sums.assign(75, std::vector<float>(n));
    planes.weights.assign(25, std::vector<float>(n));
    planes.y_min.assign(n, -1.0f);
    planes.y_max.assign(n, -1.0f);
    planes.u_min.assign(n, float(s_u));
    planes.u_max.assign(n, float(s_u));
    planes.omega_x.assign(n, float(2 / pixel_m));
    planes.id.assign(n, 1.0f);
    planes.pixel_size.assign(n, float(pixel_m));
    planes.spp.assign(n, spp);
    for (int c = 0; c < 3; ++c) {
        planes.position[c].assign(n, 0.0f);
        planes.normal[c].assign(n, c == 1 ? 1.0f : 0.0f);
    }
    Maaf6Wedge w;
    w.has_y = false;
    w.has_u = true;
    w.u_min = w.u_max = s_u;
    w.omega_u_max = 10;
    w.omega_x_max = 2 / pixel_m;
    const Maaf6SampleSide side(maaf6_pair_components(w, 3));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> lens(-0.1, 0.1);
    const double repeat = double(spp) / 16;
    for (std::size_t i = 0; i < n; ++i) {
        const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
        planes.position[0][i] = float(pixel_m * x);
        planes.position[2][i] = float(pixel_m * y);
        const double unoccluded = (x + y) % 2 ? 1.5 : 0.5;
        std::vector<double> rgb(75, 0.0), weight(25, 0.0);
        for (int s = 0; s < 16; ++s) {
            const float visible = s % 2 ? 1.0f : 0.0f;
            const float value[3] = {float(colour[0] * unoccluded) * visible,
                                    float(colour[1] * unoccluded) * visible,
                                    float(colour[2] * unoccluded) * visible};
            side.accumulate(0, lens(rng), 0, lens(rng), value, unoccluded, rgb.data(), weight.data());
        }
        for (int c = 0; c < 75; ++c) planes.sums[std::size_t(c)][i] = float(repeat * rgb[std::size_t(c)]);
        for (int c = 0; c < 25; ++c)
            planes.weights[std::size_t(c)][i] = float(repeat * weight[std::size_t(c)]);
    }
    return planes;
}

}  // namespace aaf::maaf6_test
