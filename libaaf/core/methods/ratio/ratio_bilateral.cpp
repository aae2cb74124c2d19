// The separable joint bilateral of the ratio estimator (Heitz, Hill, McGuire
// 2018, Sec. 4.1): widths from the noise estimate, plane-distance weights.
#include "aaf/core/ratio_bilateral.h"

#include <algorithm>
#include <cmath>

#include "aaf/core/error.h"
#include "aaf/core/fast_exp.h"
#include "aaf/core/parallel.h"

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
    for (std::vector<float> *v : {&planes.px, &planes.py, &planes.pz, &planes.nx, &planes.ny, &planes.nz,
                                  &planes.inv_scale})
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

/// Weight of tap t for centre c at `offset` pixels: the Gaussian in screen
/// space times the Gaussian of t's distance from c's tangent plane in units
/// of plane_sigma x c's pixel footprint (scene scale, not absolute depth).
inline float tap_weight(const Planes &planes, std::size_t c, std::size_t t, float minus_half_inv_sigma_sq,
                        int offset) {
    if (planes.inv_scale[t] == 0) return 0.0f;
    const float d = (planes.px[t] - planes.px[c]) * planes.nx[c] + (planes.py[t] - planes.py[c]) * planes.ny[c] +
                    (planes.pz[t] - planes.pz[c]) * planes.nz[c];
    const float q = d * planes.inv_scale[c];
    return fast_exp_nonpositive(minus_half_inv_sigma_sq * float(offset * offset) - 0.5f * q * q);
}

void check_inputs(const Planes &planes, ConstPlaneView sigma_px, const std::vector<std::vector<float>> &sources) {
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
    if (sources.empty() || sources.size() > kMaxPlanes) throw Error("ratio bilateral: 1 to 8 planes per pass");
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
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t c = planes.index(x, y);
            float g = 0;
            const int radius = radius_of(x, y, g);
            float *out = &horizontal[c * k_count];
            if (radius == 0) {
                std::copy_n(&interleaved[c * k_count], k_count, out);
                continue;
            }
            float sums[kMaxPlanes] = {};
            float weight_sum = 0;
            for (int tx = std::max(0, x - radius); tx <= std::min(width - 1, x + radius); ++tx) {
                const std::size_t t = planes.index(tx, y);
                const float w = tx == x ? 1.0f : tap_weight(planes, c, t, g, tx - x);
                weight_sum += w;
                const float *value = &interleaved[t * k_count];
                for (std::size_t k = 0; k < k_count; ++k) sums[k] += w * value[k];
            }
            for (std::size_t k = 0; k < k_count; ++k) out[k] = sums[k] / weight_sum;
        }
    });
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t c = planes.index(x, y);
            float g = 0;
            const int radius = radius_of(x, y, g);
            if (radius == 0) {
                sink(x, y, &horizontal[c * k_count]);
                continue;
            }
            float sums[kMaxPlanes] = {};
            float weight_sum = 0;
            for (int ty = std::max(0, y - radius); ty <= std::min(height - 1, y + radius); ++ty) {
                const std::size_t t = planes.index(x, ty);
                const float w = ty == y ? 1.0f : tap_weight(planes, c, t, g, ty - y);
                weight_sum += w;
                const float *value = &horizontal[t * k_count];
                for (std::size_t k = 0; k < k_count; ++k) sums[k] += w * value[k];
            }
            for (std::size_t k = 0; k < k_count; ++k) sums[k] /= weight_sum;
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
