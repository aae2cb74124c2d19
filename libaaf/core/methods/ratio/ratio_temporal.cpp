// Temporal integration of the ratio estimator's output by reverse
// reprojection (Heitz, Hill, McGuire 2018, Sec. 4.1 pass 5).
#include "aaf/core/methods/ratio/ratio_temporal.h"

#include <cmath>
#include <vector>

#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

void check_frame(const TemporalFrame &frame, int width, int height, const char *which) {
    auto check = [&](ConstPlaneView view) {
        if (!view.valid() || view.width != width || view.height != height)
            throw Error(std::string("temporal accumulation: the ") + which +
                        " frame's layers differ in size");
    };
    for (int c = 0; c < 3; ++c) {
        check(frame.colour[c]);
        check(frame.position[c]);
        check(frame.normal[c]);
    }
    check(frame.scale_m);
}

}  // namespace

void temporal_accumulate(const TemporalFrame &current, const std::array<ConstPlaneView, 2> &motion,
                         const TemporalFrame &previous, const TemporalSettings &settings,
                         const std::array<PlaneView, 3> &out) {
    const int width = current.colour[0].width, height = current.colour[0].height;
    check_frame(current, width, height, "current");
    check_frame(previous, width, height, "previous");
    for (int c = 0; c < 2; ++c)
        if (!motion[c].valid() || motion[c].width != width || motion[c].height != height)
            throw Error("temporal accumulation: the motion layer is missing or has another size");
    for (int c = 0; c < 3; ++c)
        if (!out[c].valid() || out[c].width != width || out[c].height != height)
            throw Error("temporal accumulation: an output is missing or has another size");
    if (!(settings.alpha > 0 && settings.alpha <= 1) || !(settings.plane_tolerance > 0))
        throw Error("temporal accumulation: alpha must be in (0, 1] and the plane tolerance > 0");
    const float min_cos = std::cos(settings.normal_threshold_deg * 3.14159265f / 180.0f);

    std::vector<float> result(std::size_t(width) * std::size_t(height) * 3);
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            float now[3];
            for (int c = 0; c < 3; ++c) now[c] = current.colour[c](x, y);
            float *dst = &result[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
            for (int c = 0; c < 3; ++c) dst[c] = now[c];
            const float p[3] = {current.position[0](x, y), current.position[1](x, y),
                                current.position[2](x, y)};
            const float n[3] = {current.normal[0](x, y), current.normal[1](x, y), current.normal[2](x, y)};
            const float scale = current.scale_m(x, y);
            const float mx = motion[0](x, y), my = motion[1](x, y);
            if (!(scale > 0) || !std::isfinite(scale + p[0] + p[1] + p[2] + n[0] + n[1] + n[2] + mx + my))
                continue;
            // Where the surface was: raster position minus motion; pixel centres at +0.5.
            const float fx = float(x) - mx, fy = float(y) - my;
            const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
            const float ax = fx - float(x0), ay = fy - float(y0);
            double weight_sum = 0, sums[3] = {0, 0, 0};
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 2; ++i) {
                    const int tx = x0 + i, ty = y0 + j;
                    const float w = (i ? ax : 1 - ax) * (j ? ay : 1 - ay);
                    if (w <= 0 || tx < 0 || ty < 0 || tx >= width || ty >= height) continue;
                    const float q[3] = {previous.position[0](tx, ty), previous.position[1](tx, ty),
                                        previous.position[2](tx, ty)};
                    const float m[3] = {previous.normal[0](tx, ty), previous.normal[1](tx, ty),
                                        previous.normal[2](tx, ty)};
                    const float h[3] = {previous.colour[0](tx, ty), previous.colour[1](tx, ty),
                                        previous.colour[2](tx, ty)};
                    if (!std::isfinite(q[0] + q[1] + q[2] + m[0] + m[1] + m[2] + h[0] + h[1] + h[2]))
                        continue;
                    // Disocclusion: the previous surface must lie on this pixel's tangent plane ...
                    const float d = (q[0] - p[0]) * n[0] + (q[1] - p[1]) * n[1] + (q[2] - p[2]) * n[2];
                    if (std::fabs(d) > settings.plane_tolerance * scale) continue;
                    // ... and face the same way.
                    const float n_len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                    const float m_len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
                    if (!(n_len > 0) || !(m_len > 0) ||
                        (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]) < min_cos * n_len * m_len)
                        continue;
                    weight_sum += w;
                    for (int c = 0; c < 3; ++c) sums[c] += double(w) * h[c];
                }
            if (weight_sum < 1e-3) continue;
            for (int c = 0; c < 3; ++c)  // exponential history
                dst[c] = settings.alpha * now[c] + (1 - settings.alpha) * float(sums[c] / weight_sum);
        }
    });
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                out[c](x, y) =
                    result[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3 + std::size_t(c)];
}

}  // namespace aaf
