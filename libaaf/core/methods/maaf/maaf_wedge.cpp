#include "aaf/core/methods/maaf/maaf_wedge.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "aaf/core/methods/aaf/occluder_fill.h"
#include "aaf/core/methods/maaf/maaf_components.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

constexpr float kPi = 3.14159265358979323846f;

void check_size(ConstPlaneView view, int width, int height, const char *what) {
    if (!view.valid() || view.width != width || view.height != height)
        throw Error(std::string("MAAF input '") + what + "' is missing or has another size");
}

/// The per-pixel wedge slopes before MAAF's prefilter, and the unit normals
/// (0 where the normal is unusable) that decide which neighbours it averages.
struct RawSlopes {
    std::vector<float> s_min, s_max, unit_normal;
};

/// Raw slopes (MAAF Sec. 3: s = d1/d2 - 1), NaN where a pixel has no wedge.
RawSlopes raw_slopes(const MaafWedgeInputs &in, const FilledOccluders &occluders) {
    const int width = in.d1.width, height = in.d1.height;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    const float no_wedge = std::nanf("");
    RawSlopes raw{std::vector<float>(count, no_wedge), std::vector<float>(count, no_wedge),
                  std::vector<float>(3 * count, 0.0f)};
    std::vector<float> &raw_min = raw.s_min, &raw_max = raw.s_max, &unit_normal = raw.unit_normal;
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            const float nx = in.normal[0](x, y), ny = in.normal[1](x, y), nz = in.normal[2](x, y);
            const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
            if (len > 0 && std::isfinite(len)) {
                unit_normal[3 * i] = nx / len;
                unit_normal[3 * i + 1] = ny / len;
                unit_normal[3 * i + 2] = nz / len;
            }
            const float d1 = in.d1(x, y), d2_min = occluders.d2_min_m[i], d2_max = occluders.d2_max_m[i];
            const float pixel = in.pixel_size(x, y);
            if (in.object_id(x, y) == 0 || !(d1 > 0) || !std::isfinite(d1) || !(pixel > 0) ||
                !std::isfinite(pixel) || !has_occluder(d2_max) || !(d2_min > 0))
                continue;
            // An occluder measured beyond the receiver (curved geometry) counts as contact.
            raw_min[i] = std::max(0.0f, d1 / d2_max - 1.0f);
            raw_max[i] = std::max(raw_min[i], d1 / d2_min - 1.0f);
        }
    });
    return raw;
}

}  // namespace

void MaafWedgeParams::validate() const {
    if (!(light_band > 0) || !std::isfinite(light_band))
        throw Error("MAAF light band must be positive and finite");
    if (fill_radius_px < 0) throw Error("MAAF fill radius must be >= 0 pixels");
    if (prefilter_radius_px < 0) throw Error("MAAF prefilter radius must be >= 0 pixels");
    if (!(normal_threshold_deg >= 0 && normal_threshold_deg <= 180))
        throw Error("MAAF normal threshold must lie in [0, 180] degrees");
}

double maaf_light_omega_y_max(const LightPlane &light, double light_band) {
    return light_band / double(light.sigma_m);  // MAAF Sec. 3: Omega_y^max = 2 / sigma_y for light_band 2
}

MaafWedges maaf_pixel_wedges(const MaafWedgeInputs &in, const LightPlane &light,
                             const MaafWedgeParams &params) {
    params.validate();
    light.validate();
    const int width = in.d1.width, height = in.d1.height;
    if (width <= 0 || height <= 0) throw Error("MAAF input 'd1' is missing or empty");
    check_size(in.d2_min, width, height, "d2min");
    check_size(in.d2_max, width, height, "d2max");
    for (const ConstPlaneView &n : in.normal) check_size(n, width, height, "normal");
    check_size(in.object_id, width, height, "object_id");
    check_size(in.pixel_size, width, height, "pixel_size");

    const std::size_t count = std::size_t(width) * std::size_t(height);
    const double omega_y_light = maaf_light_omega_y_max(light, params.light_band);
    // AAF Sec. 6: unoccluded pixels take the occluder distances of their neighbours.
    const FilledOccluders occluders =
        fill_occluder_distances(in.d2_min, in.d2_max, in.object_id, params.fill_radius_px);

    const RawSlopes raw = raw_slopes(in, occluders);
    const std::vector<float> &raw_min = raw.s_min, &raw_max = raw.s_max, &unit_normal = raw.unit_normal;

    MaafWedges w;
    w.width = width;
    w.height = height;
    w.s_min.assign(count, 0.0f);
    w.s_max.assign(count, 0.0f);
    w.omega_x_max.assign(count, 0.0f);
    w.omega_y.assign(count, float(omega_y_light));
    const float cos_threshold = std::cos(params.normal_threshold_deg * kPi / 180.0f);
    const int r = params.prefilter_radius_px;
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            if (std::isnan(raw_min[i])) continue;
            // MAAF Sec. 6.2: slopes averaged over the 5x5 window, same object, normals within the threshold.
            const float id = in.object_id(x, y);
            double sum_min = 0, sum_max = 0;
            int used = 0;
            for (int ty = std::max(0, y - r); ty <= std::min(height - 1, y + r); ++ty)
                for (int tx = std::max(0, x - r); tx <= std::min(width - 1, x + r); ++tx) {
                    const std::size_t t = std::size_t(ty) * std::size_t(width) + std::size_t(tx);
                    if (std::isnan(raw_min[t]) || in.object_id(tx, ty) != id) continue;
                    const float cos_angle = unit_normal[3 * i] * unit_normal[3 * t] +
                                            unit_normal[3 * i + 1] * unit_normal[3 * t + 1] +
                                            unit_normal[3 * i + 2] * unit_normal[3 * t + 2];
                    if (t != i && !(cos_angle >= cos_threshold)) continue;
                    sum_min += raw_min[t];
                    sum_max += raw_max[t];
                    ++used;
                }
            const double s_min = sum_min / used, s_max = std::max(s_min, sum_max / used);
            // AAF Eq. 6 on MAAF's scale (MaafWedgeParams::light_band), rad/m.
            const double omega_x_max =
                std::min(params.light_band / ((1.0 + s_min) * double(in.pixel_size(x, y))),
                         double(std::numeric_limits<float>::max()));
            w.s_min[i] = float(s_min);
            w.s_max[i] = float(s_max);
            w.omega_x_max[i] = float(omega_x_max);
            // Stored as floats: the partition is computed from the stored values, as a filter reading them
            // will.
            w.omega_y[i] = float(maaf_partitioned_omega_y_max(double(w.s_min[i]), double(w.s_max[i]),
                                                              double(w.omega_x_max[i]), omega_y_light));
        }
    });
    return w;
}

}  // namespace aaf
