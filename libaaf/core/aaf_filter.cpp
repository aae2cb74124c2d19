#include "aaf/core/aaf_filter.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/aaf_bandlimits.h"
#include "aaf/core/error.h"
#include "aaf/core/fast_exp.h"
#include "aaf/core/occluder_fill.h"
#include "aaf/core/parallel.h"

namespace aaf {

namespace {

constexpr float kPi = 3.14159265358979323846f;
/// Taps stop at 3 beta, where the Gaussian weight has fallen to exp(-4.5).
constexpr float kCutoffSigmas = 3.0f;

void check_size(ConstPlaneView view, int width, int height, const char *what) {
    if (!view.valid() || view.width != width || view.height != height)
        throw Error(std::string("AAF input '") + what + "' is missing or has another size");
}

/// Per-pixel state shared by the passes, as planar arrays so the tap loops vectorise.
struct PixelFrame {
    int width = 0, height = 0;
    // Position in the light's plane: coordinates along its two tangent axes, so
    // du^2 + dv^2 = |x - x'|^2 - [n . (x - x')]^2 (AAF Eq. 12) for the orthonormal frame.
    std::vector<float> plane_u, plane_v;
    std::vector<float> normal_x, normal_y, normal_z;  // unit, or zero where unusable
    std::vector<float> object_id;
    std::vector<float> beta_m;           // 0 = not filtered
    std::vector<float> inv_two_beta_sq;  // 1 / (2 beta^2), metres^-2
    std::vector<int> radius_px;          // 0 = not filtered

    std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }
};

PixelFrame build_frame(const AafInputs &in, const LightPlane &light, const AafParams &params) {
    PixelFrame frame;
    frame.width = in.visibility.width;
    frame.height = in.visibility.height;
    const std::size_t count = std::size_t(frame.width) * frame.height;
    for (std::vector<float> *plane :
         {&frame.plane_u, &frame.plane_v, &frame.normal_x, &frame.normal_y, &frame.normal_z, &frame.object_id,
          &frame.beta_m, &frame.inv_two_beta_sq})
        plane->assign(count, 0.0f);
    frame.radius_px.assign(count, 0);

    // AAF Sec. 6: unoccluded pixels take the occluder distances of their neighbours.
    const FilledOccluders occluders =
        fill_occluder_distances(in.d2_min, in.d2_max, in.object_id, params.fill_radius_px);

    parallel_for_rows(frame.height, [&](int y) {
        for (int x = 0; x < frame.width; ++x) {
            const std::size_t i = frame.index(x, y);
            const Vec3 p{in.position[0](x, y), in.position[1](x, y), in.position[2](x, y)};
            frame.plane_u[i] = dot(light.axis_u, p - light.center);
            frame.plane_v[i] = dot(light.axis_v, p - light.center);
            const Vec3 n{in.normal[0](x, y), in.normal[1](x, y), in.normal[2](x, y)};
            const float len = length(n);
            const Vec3 unit = (len > 0 && std::isfinite(len)) ? n / len : Vec3{};
            frame.normal_x[i] = unit.x;
            frame.normal_y[i] = unit.y;
            frame.normal_z[i] = unit.z;
            frame.object_id[i] = in.object_id(x, y);

            const float d1 = in.d1(x, y), pixel_size = in.pixel_size(x, y);
            const float d2_min = occluders.d2_min_m[i], d2_max = occluders.d2_max_m[i];
            if (frame.object_id[i] == 0 || !(d1 > 0) || !(pixel_size > 0) || !std::isfinite(pixel_size) ||
                !has_occluder(d2_max) || !std::isfinite(frame.plane_u[i] + frame.plane_v[i]))
                continue;
            AafParams pixel_params = params;
            if (params.mu_from_spp)  // Sec. 5.2: the filter follows the samples actually taken
                pixel_params.mu =
                    mu_for_samples(in.spp(x, y), d1, d2_min, d2_max, pixel_size, light.sigma_m, params);
            const float beta =
                params.fixed_beta_m > 0
                    ? params.fixed_beta_m
                    : aaf_bandlimits(d1, d2_min, d2_max, pixel_size, light.sigma_m, pixel_params).beta_m;
            if (!(beta > 0) || !std::isfinite(beta)) continue;
            // beta is in world metres; the reach in pixels follows from the pixel's footprint.
            const float radius =
                std::min(std::ceil(kCutoffSigmas * beta / pixel_size), float(params.max_radius_px));
            frame.beta_m[i] = beta;
            frame.inv_two_beta_sq[i] = 1.0f / (2.0f * beta * beta);
            frame.radius_px[i] = int(radius);
        }
    });
    return frame;
}

/// The same frame with rows and columns swapped, so a vertical pass runs as a
/// horizontal one over contiguous memory.
PixelFrame transposed(const PixelFrame &f) {
    PixelFrame t;
    t.width = f.height;
    t.height = f.width;
    auto swap_axes = [&](const auto &plane, auto &out) {
        out.resize(plane.size());
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) out[std::size_t(x) * f.height + y] = plane[f.index(x, y)];
    };
    swap_axes(f.plane_u, t.plane_u);
    swap_axes(f.plane_v, t.plane_v);
    swap_axes(f.normal_x, t.normal_x);
    swap_axes(f.normal_y, t.normal_y);
    swap_axes(f.normal_z, t.normal_z);
    swap_axes(f.object_id, t.object_id);
    swap_axes(f.beta_m, t.beta_m);
    swap_axes(f.inv_two_beta_sq, t.inv_two_beta_sq);
    swap_axes(f.radius_px, t.radius_px);
    return t;
}

std::vector<float> transposed(const std::vector<float> &plane, int width, int height) {
    std::vector<float> out(plane.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) out[std::size_t(x) * height + y] = plane[std::size_t(y) * width + x];
    return out;
}

/// Taps accumulated in kLanes interleaved partial sums: a fixed summation
/// order (so results do not depend on threads or build flags) that the
/// compiler can still map onto SIMD lanes.
constexpr int kLanes = 8;

/// Gathers one pixel over the taps at offsets (ox, oy), |ox| <= reach_x,
/// |oy| <= reach_y: the normalised sum of `source` weighted by the Gaussian of
/// AAF Eq. 11 (its normalisation cancels) of the light-plane distance of
/// Eq. 12. A tap counts when it lies on the same object and its normal is
/// within the threshold. The centre always counts: if its own test fails (a
/// NaN or zero normal), it is added back with weight 1.
float gather_pixel(const PixelFrame &f, float cos_threshold, const float *source, int x, int y, int reach_x,
                   int reach_y) {
    const std::size_t c = f.index(x, y);
    const float u = f.plane_u[c], v = f.plane_v[c], id = f.object_id[c];
    const float nx = f.normal_x[c], ny = f.normal_y[c], nz = f.normal_z[c];
    const float inv_two_beta_sq = f.inv_two_beta_sq[c];
    const int x_begin = std::max(0, x - reach_x), x_end = std::min(f.width, x + reach_x + 1);
    const int y_begin = std::max(0, y - reach_y), y_end = std::min(f.height, y + reach_y + 1);

    float sum[kLanes] = {}, weight_sum[kLanes] = {};
    auto accumulate = [&](std::size_t t, int lane) {
        const float cos_angle = nx * f.normal_x[t] + ny * f.normal_y[t] + nz * f.normal_z[t];
        const float accepted = float(f.object_id[t] == id) * float(cos_angle >= cos_threshold);
        const float du = f.plane_u[t] - u, dv = f.plane_v[t] - v;
        const float weight =
            accepted * fast_exp_nonpositive(-(du * du + dv * dv) * inv_two_beta_sq);  // Eq. 11
        sum[lane] += weight * source[t];
        weight_sum[lane] += weight;
    };
    for (int ty = y_begin; ty < y_end; ++ty) {
        const std::size_t row = std::size_t(ty) * f.width;
        int tx = x_begin;
        for (; tx + kLanes <= x_end; tx += kLanes)
            for (int lane = 0; lane < kLanes; ++lane) accumulate(row + tx + lane, lane);
        for (int lane = 0; tx < x_end; ++tx, ++lane) accumulate(row + tx, lane);
    }
    float total = 0, total_weight = 0;
    for (int lane = 0; lane < kLanes; ++lane) {
        total += sum[lane];
        total_weight += weight_sum[lane];
    }
    const bool centre_counted = (nx * nx + ny * ny + nz * nz) >= cos_threshold && id == id;
    if (!centre_counted) {
        total += source[c];
        total_weight += 1.0f;
    }
    return total / total_weight;
}

/// One gather over the image along the enabled axes, each pixel within its
/// own radius. Pixels with radius 0 keep their value. Rows run in parallel;
/// every pixel's sum has a fixed order, so threads cannot change the result.
void gather(const PixelFrame &f, float cos_threshold, const std::vector<float> &source, bool along_x,
            bool along_y, std::vector<float> &out) {
    parallel_for_rows(f.height, [&](int y) {
        for (int x = 0; x < f.width; ++x) {
            const std::size_t c = f.index(x, y);
            const int radius = f.radius_px[c];
            out[c] = radius == 0 ? source[c]
                                 : gather_pixel(f, cos_threshold, source.data(), x, y, along_x ? radius : 0,
                                                along_y ? radius : 0);
        }
    });
}

}  // namespace

void aaf_filter(const AafInputs &in, const LightPlane &light, const AafParams &params,
                const AafOutputs &out) {
    params.validate();
    light.validate();
    const int width = in.visibility.width, height = in.visibility.height;
    if (width <= 0 || height <= 0) throw Error("AAF input 'visibility' is missing or empty");
    check_size(in.d1, width, height, "d1");
    check_size(in.d2_min, width, height, "d2min");
    check_size(in.d2_max, width, height, "d2max");
    for (int c = 0; c < 3; ++c) {
        check_size(in.position[c], width, height, "position");
        check_size(in.normal[c], width, height, "normal");
    }
    check_size(in.object_id, width, height, "object_id");
    check_size(in.pixel_size, width, height, "pixel_size");
    if (params.mu_from_spp) check_size(in.spp, width, height, "spp");
    if (!out.filtered_visibility.valid() || out.filtered_visibility.width != width ||
        out.filtered_visibility.height != height)
        throw Error("AAF output 'filtered visibility' is missing or has another size");
    if (out.beta_m.valid() && (out.beta_m.width != width || out.beta_m.height != height))
        throw Error("AAF output 'beta' has another size");

    const PixelFrame frame = build_frame(in, light, params);
    // Normals are unit, so their dot product is the cosine; no acos is needed.
    const float cos_threshold = std::cos(params.normal_threshold_deg * kPi / 180.0f);

    // Non-finite visibility (a renderer's NaN) is read as 0, so it cannot spread through the filter.
    std::vector<float> visibility(std::size_t(width) * height), filtered(visibility.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float v = in.visibility(x, y);
            visibility[frame.index(x, y)] = std::isfinite(v) ? v : 0.0f;
        }

    if (params.mode == AafFilterMode::Separable) {
        // w(x_ij - x_kl) = w(x_ij - x_kj) w(x_kj - x_kl) (Sec. 6): gather along
        // columns into (k, j), then along the row into (i, j).
        // The vertical pass runs on the transposed image, over contiguous taps.
        const PixelFrame frame_t = transposed(frame);
        std::vector<float> vertical_t(visibility.size());
        gather(frame_t, cos_threshold, transposed(visibility, width, height), true, false, vertical_t);
        gather(frame, cos_threshold, transposed(vertical_t, height, width), true, false, filtered);
    } else {
        gather(frame, cos_threshold, visibility, true, true, filtered);  // Eq. 10 directly
    }

    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            out.filtered_visibility(x, y) = filtered[frame.index(x, y)];
            if (out.beta_m.valid()) out.beta_m(x, y) = frame.beta_m[frame.index(x, y)];
        }
}

}  // namespace aaf
