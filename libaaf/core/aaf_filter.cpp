#include "aaf/core/aaf_filter.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/aaf_bandlimits.h"
#include "aaf/core/error.h"
#include "aaf/core/occluder_fill.h"
#include "aaf/core/parallel.h"

namespace aaf {

namespace {

constexpr float kPi = 3.14159265358979323846f;
/// The Gaussian is cut where its weight falls below exp(-4.5), at 3 beta.
constexpr float kCutoffSigmas = 3.0f;

Vec3 read3(const std::array<ConstPlaneView, 3> &planes, int x, int y) {
    return {planes[0](x, y), planes[1](x, y), planes[2](x, y)};
}

void check_size(ConstPlaneView view, int width, int height, const char *what) {
    if (!view.valid() || view.width != width || view.height != height)
        throw Error(std::string("AAF input '") + what + "' is missing or has another size");
}

/// Per-pixel state shared by the two passes.
struct PixelFrame {
    int width = 0, height = 0;
    std::vector<Vec3> position;
    std::vector<Vec3> normal;        // unit, or zero where unusable
    std::vector<float> object_id;
    std::vector<float> beta_m;       // 0 = not filtered
    std::vector<int> radius_px;      // 0 = not filtered

    std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }
};

PixelFrame build_frame(const AafInputs &in, const LightPlane &light, const AafParams &params) {
    PixelFrame frame;
    frame.width = in.visibility.width;
    frame.height = in.visibility.height;
    const std::size_t count = std::size_t(frame.width) * frame.height;
    frame.position.resize(count);
    frame.normal.resize(count);
    frame.object_id.resize(count);
    frame.beta_m.assign(count, 0.0f);
    frame.radius_px.assign(count, 0);

    parallel_for_rows(frame.height, [&](int y) {
        for (int x = 0; x < frame.width; ++x) {
            const std::size_t i = frame.index(x, y);
            frame.position[i] = read3(in.position, x, y);
            Vec3 n = read3(in.normal, x, y);
            float len = length(n);
            frame.normal[i] = (len > 0 && std::isfinite(len)) ? n / len : Vec3{};
            frame.object_id[i] = in.object_id(x, y);
        }
    });

    // AAF Sec. 6: unoccluded pixels take the occluder distances of their neighbours.
    const FilledOccluders occluders =
        fill_occluder_distances(in.d2_min, in.d2_max, in.object_id, params.fill_radius_px);

    parallel_for_rows(frame.height, [&](int y) {
        for (int x = 0; x < frame.width; ++x) {
            const std::size_t i = frame.index(x, y);
            const float d1 = in.d1(x, y);
            const float pixel_size = in.pixel_size(x, y);
            if (frame.object_id[i] == 0 || !(d1 > 0) || !(pixel_size > 0) || !std::isfinite(pixel_size))
                continue;
            const float d2_min = occluders.d2_min_m[i], d2_max = occluders.d2_max_m[i];
            if (!has_occluder(d2_max)) continue;
            const float beta = aaf_bandlimits(d1, d2_min, d2_max, pixel_size, light.sigma_m, params).beta_m;
            if (!(beta > 0) || !std::isfinite(beta)) continue;
            // beta is in world metres; the pixel radius follows from the pixel's footprint.
            const float radius = std::ceil(kCutoffSigmas * beta / pixel_size);
            frame.beta_m[i] = beta;
            frame.radius_px[i] = int(std::min(radius, float(params.max_radius_px)));
        }
    });
    return frame;
}

/// One 1D pass of the separable filter (AAF Sec. 6): out(x, y) is the
/// normalised Gaussian average of `source` along the direction (step_x, step_y)
/// with weight w(x - x'; beta(x)) of Eq. 11, distances from Eq. 12.
void filter_pass(const PixelFrame &frame, const LightPlane &light, float cos_threshold,
                 const std::vector<float> &source, int step_x, int step_y, std::vector<float> &out) {
    parallel_for_rows(frame.height, [&](int y) {
        for (int x = 0; x < frame.width; ++x) {
            const std::size_t centre = frame.index(x, y);
            const int radius = frame.radius_px[centre];
            if (radius == 0) {
                out[centre] = source[centre];
                continue;
            }
            const float inv_two_beta_sq = 1.0f / (2.0f * frame.beta_m[centre] * frame.beta_m[centre]);
            const Vec3 p = frame.position[centre];
            const Vec3 n = frame.normal[centre];
            const float id = frame.object_id[centre];
            // The centre tap is always taken; rejection tests apply to the others only.
            double weighted_sum = source[centre];
            double weight_sum = 1.0;
            for (int offset = -radius; offset <= radius; ++offset) {
                if (offset == 0) continue;
                const int tx = x + offset * step_x, ty = y + offset * step_y;
                if (tx < 0 || ty < 0 || tx >= frame.width || ty >= frame.height) continue;
                const std::size_t tap = frame.index(tx, ty);
                if (frame.object_id[tap] != id) continue;
                // Normals are unit or zero; clamp before comparing so rounding cannot reject.
                const float cos_angle = std::clamp(dot(n, frame.normal[tap]), -1.0f, 1.0f);
                if (!(cos_angle >= cos_threshold)) continue;
                const float dist_sq = light.in_plane_distance_sq(p, frame.position[tap]);  // Eq. 12
                if (!std::isfinite(dist_sq)) continue;
                const float weight = std::exp(-dist_sq * inv_two_beta_sq);  // Eq. 11, unnormalised
                weighted_sum += double(weight) * source[tap];
                weight_sum += weight;
            }
            out[centre] = float(weighted_sum / weight_sum);
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
    if (!out.filtered_visibility.valid() || out.filtered_visibility.width != width ||
        out.filtered_visibility.height != height)
        throw Error("AAF output 'filtered visibility' is missing or has another size");
    if (out.beta_m.valid() && (out.beta_m.width != width || out.beta_m.height != height))
        throw Error("AAF output 'beta' has another size");

    const PixelFrame frame = build_frame(in, light, params);
    const float cos_threshold = std::cos(params.normal_threshold_deg * kPi / 180.0f);

    std::vector<float> visibility(frame.position.size()), vertical(visibility.size()),
        filtered(visibility.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) visibility[frame.index(x, y)] = in.visibility(x, y);

    // w(x_ij - x_kl) = w(x_ij - x_kj) w(x_kj - x_kl) (Sec. 6): gather along
    // columns into (k, j), then along the row into (i, j).
    filter_pass(frame, light, cos_threshold, visibility, 0, 1, vertical);
    filter_pass(frame, light, cos_threshold, vertical, 1, 0, filtered);

    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            out.filtered_visibility(x, y) = filtered[frame.index(x, y)];
            if (out.beta_m.valid()) out.beta_m(x, y) = frame.beta_m[frame.index(x, y)];
        }
}

}  // namespace aaf
