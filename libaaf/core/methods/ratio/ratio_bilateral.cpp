// The separable joint bilateral of the ratio estimator (Heitz, Hill, McGuire
// 2018, Sec. 4.1): widths from the noise estimate, plane-distance weights.
#include "aaf/core/methods/ratio/ratio_bilateral.h"

#include <algorithm>
#include <cmath>

#include "aaf/core/kernels/fast_exp.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

/// Per-pixel tangent planes in packed form; scale 0 marks "not a surface".
struct Planes {
    int width = 0, height = 0;
    std::vector<float> px, py, pz, nx, ny, nz, inv_scale;  ///< inv_scale: 1 / (plane_sigma scale_m)
    std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width) + std::size_t(x); }
};

Planes planes_from(const RatioBilateralGuides &guides, float plane_sigma) {
    Planes planes;
    planes.width = guides.scale_m.width;
    planes.height = guides.scale_m.height;
    const std::size_t count = std::size_t(planes.width) * std::size_t(planes.height);
    for (std::vector<float> *v :
         {&planes.px, &planes.py, &planes.pz, &planes.nx, &planes.ny, &planes.nz, &planes.inv_scale})
        v->assign(count, 0.0f);
    parallel_for_rows(planes.height, [&](int y) {
        for (int x = 0; x < planes.width; ++x) {
            const std::size_t i = planes.index(x, y);
            const float p[3] = {guides.position[0](x, y), guides.position[1](x, y), guides.position[2](x, y)};
            float n[3] = {guides.normal[0](x, y), guides.normal[1](x, y), guides.normal[2](x, y)};
            const float scale = guides.scale_m(x, y);
            const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(scale > 0) || !std::isfinite(scale) || !std::isfinite(p[0] + p[1] + p[2]) ||
                !(length > 0) || !std::isfinite(length))
                continue;
            planes.px[i] = p[0];
            planes.py[i] = p[1];
            planes.pz[i] = p[2];
            planes.nx[i] = n[0] / length;
            planes.ny[i] = n[1] / length;
            planes.nz[i] = n[2] / length;
            planes.inv_scale[i] = 1.0f / (plane_sigma * scale);
        }
    });
    return planes;
}

/// The weights of `count` taps from pixel index `first` in steps of
/// `stride`, the first at `offset` pixels from centre c: a branch-free loop
/// over the packed planes, so it vectorises.
void tap_weights(const Planes &planes, std::size_t c, std::size_t first, std::size_t stride, int offset,
                 int count, float minus_half_inv_sigma_sq, std::vector<float> &weights) {
    const float nx = planes.nx[c], ny = planes.ny[c], nz = planes.nz[c], inv_scale = planes.inv_scale[c];
    const float plane_c = nx * planes.px[c] + ny * planes.py[c] + nz * planes.pz[c];
    for (int j = 0; j < count; ++j) {
        const std::size_t t = first + std::size_t(j) * stride;
        // Distance of the tap from the centre's tangent plane, in plane_sigma footprints.
        const float q = (nx * planes.px[t] + ny * planes.py[t] + nz * planes.pz[t] - plane_c) * inv_scale;
        const float o = float(offset + j);
        const float w = fast_exp_nonpositive(minus_half_inv_sigma_sq * o * o - 0.5f * q * q);
        weights[std::size_t(j)] = planes.inv_scale[t] == 0 ? 0.0f : w;  // no surface: never a tap
    }
}

/// sums[k] = sum_j weights[j] values[j * stride + k] / sum_j weights[j], in tap order.
void accumulate(const std::vector<float> &weights, int count, const float *values, std::size_t stride,
                std::size_t k_count, float *sums) {
    float weight_sum = 0;
    for (std::size_t k = 0; k < k_count; ++k) sums[k] = 0;
    for (int j = 0; j < count; ++j) {
        const float w = weights[std::size_t(j)];
        weight_sum += w;
        const float *value = values + std::size_t(j) * stride;
        for (std::size_t k = 0; k < k_count; ++k) sums[k] += w * value[k];
    }
    for (std::size_t k = 0; k < k_count; ++k) sums[k] /= weight_sum;
}

/// The largest finite value of `view` (0 if none).
float max_finite(ConstPlaneView view) {
    float largest = 0;
    for (int y = 0; y < view.height; ++y)
        for (int x = 0; x < view.width; ++x)
            if (std::isfinite(view(x, y))) largest = std::max(largest, view(x, y));
    return largest;
}

void check_inputs(const Planes &planes, ConstPlaneView sigma_px,
                  const std::vector<std::vector<float>> &sources) {
    if (!sigma_px.valid() || sigma_px.width != planes.width || sigma_px.height != planes.height)
        throw Error("ratio bilateral: sigma is missing or has another size");
    for (const std::vector<float> &s : sources)
        if (s.size() != std::size_t(planes.width) * std::size_t(planes.height))
            throw Error("ratio bilateral: a source has another size");
}

/// At most this many planes per pass (the ratio estimator filters 6: S_N and U_N RGB).
constexpr std::size_t kMaxPlanes = 8;

/// The horizontal pass into an interleaved buffer (K floats per pixel, so a
/// tap's values share a cache line); then the vertical pass, which hands each
/// pixel's K filtered values to `sink(x, y, values)`. Sums run over the taps
/// in a fixed order, so the result does not depend on the thread count.
template <typename Sink>
void two_passes(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                const RatioBilateralSettings &settings, const std::vector<std::vector<float>> &sources,
                const Sink &sink) {
    if (!(settings.plane_sigma > 0) || !(settings.cutoff_sigmas > 0))
        throw Error("ratio bilateral: plane sigma and cut-off must be > 0");
    if (sources.empty() || sources.size() > kMaxPlanes)
        throw Error("ratio bilateral: 1 to 8 planes per pass");
    const Planes planes = planes_from(guides, settings.plane_sigma);
    check_inputs(planes, sigma_px, sources);
    const int width = planes.width, height = planes.height;
    const std::size_t k_count = sources.size(), count = planes.px.size();
    auto radius_of = [&](int x, int y, float &minus_half_inv_sigma_sq) {
        const float sigma = sigma_px(x, y);
        if (!(sigma > 0) || !std::isfinite(sigma) || planes.inv_scale[planes.index(x, y)] == 0) return 0;
        minus_half_inv_sigma_sq = -0.5f / (sigma * sigma);
        return int(std::ceil(settings.cutoff_sigmas * sigma));
    };
    std::vector<float> interleaved(count * k_count), horizontal(count * k_count);
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = planes.index(x, y);
            for (std::size_t k = 0; k < k_count; ++k) interleaved[i * k_count + k] = sources[k][i];
        }
    });
    const int max_taps = 2 * int(std::ceil(settings.cutoff_sigmas * max_finite(sigma_px))) + 1;
    parallel_for_rows(height, [&](int y) {
        std::vector<float> weights(std::size_t(std::max(max_taps, 1)));
        for (int x = 0; x < width; ++x) {
            const std::size_t c = planes.index(x, y);
            float g = 0;
            const int radius = radius_of(x, y, g);
            float *out = &horizontal[c * k_count];
            if (radius == 0) {
                std::copy_n(&interleaved[c * k_count], k_count, out);
                continue;
            }
            const int first = std::max(0, x - radius), last = std::min(width - 1, x + radius);
            tap_weights(planes, c, planes.index(first, y), 1, first - x, last - first + 1, g, weights);
            weights[std::size_t(x - first)] = 1.0f;  // the centre always counts
            accumulate(weights, last - first + 1, &interleaved[planes.index(first, y) * k_count], k_count,
                       k_count, out);
        }
    });
    parallel_for_rows(height, [&](int y) {
        std::vector<float> weights(std::size_t(std::max(max_taps, 1)));
        for (int x = 0; x < width; ++x) {
            const std::size_t c = planes.index(x, y);
            float g = 0;
            const int radius = radius_of(x, y, g);
            if (radius == 0) {
                sink(x, y, &horizontal[c * k_count]);
                continue;
            }
            const int first = std::max(0, y - radius), last = std::min(height - 1, y + radius);
            tap_weights(planes, c, planes.index(x, first), std::size_t(width), first - y, last - first + 1, g,
                        weights);
            weights[std::size_t(y - first)] = 1.0f;
            float sums[kMaxPlanes];
            accumulate(weights, last - first + 1, &horizontal[planes.index(x, first) * k_count],
                       std::size_t(width) * k_count, k_count, sums);
            sink(x, y, sums);
        }
    });
}

}  // namespace

void ratio_bilateral_compose(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                             const RatioBilateralSettings &settings,
                             const std::vector<std::vector<float>> &sources,
                             const RatioComposition &composition, const std::array<PlaneView, 3> &rgb,
                             bool accumulate) {
    if (int(sources.size()) != composition.plane_count())
        throw Error("ratio bilateral: the sources do not match the estimator");
    for (const PlaneView &out : rgb)
        if (!out.valid() || out.width != sigma_px.width || out.height != sigma_px.height)
            throw Error("ratio bilateral: an output is missing or has another size");
    // Sec. 4.1 pass 4: the vertical pass writes the final radiance directly.
    two_passes(guides, sigma_px, settings, sources, [&](int x, int y, const float *values) {
        float pixel[3] = {rgb[0](x, y), rgb[1](x, y), rgb[2](x, y)};
        composition.compose(x, y, values, pixel, accumulate);
        for (int c = 0; c < 3; ++c) rgb[c](x, y) = pixel[c];
    });
}

void ratio_bilateral(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                     const RatioBilateralSettings &settings, const std::vector<std::vector<float>> &sources,
                     const std::vector<PlaneView> &outputs) {
    if (outputs.size() != sources.size()) throw Error("ratio bilateral: as many outputs as sources needed");
    for (const PlaneView &out : outputs)
        if (!out.valid() || out.width != sigma_px.width || out.height != sigma_px.height)
            throw Error("ratio bilateral: an output is missing or has another size");
    two_passes(guides, sigma_px, settings, sources, [&](int x, int y, const float *values) {
        for (std::size_t k = 0; k < outputs.size(); ++k) outputs[k](x, y) = values[k];
    });
}

}  // namespace aaf
