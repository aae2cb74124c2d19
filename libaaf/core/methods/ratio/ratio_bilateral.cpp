// The separable joint bilateral of the ratio estimator (Heitz, Hill, McGuire
// 2018, Sec. 4.1): widths from the noise estimate, plane-distance weights.
#include "aaf/core/methods/ratio/ratio_bilateral.h"

#include <algorithm>
#include <cmath>

#include "aaf/core/methods/ratio/ratio_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

using detail::RatioBilateralPlanes;

/// The centre's Gaussian of one pixel: sigma_px there, 0 reach where it is
/// not a positive finite width or the pixel is no surface.
void set_reach(RatioBilateralPlanes &planes, std::size_t i, float sigma_px, float cutoff_sigmas) {
    if (!(sigma_px > 0) || !std::isfinite(sigma_px) || planes.inv_scale[i] == 0) return;
    planes.minus_half_inv_sigma_sq[i] = -0.5f / (sigma_px * sigma_px);
    planes.radius_px[i] = int(std::ceil(cutoff_sigmas * sigma_px));
}

/// Per-pixel tangent planes and Gaussians in packed form; inv_scale 0 marks "not a surface".
RatioBilateralPlanes planes_from(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                                 const RatioBilateralSettings &settings) {
    RatioBilateralPlanes planes;
    planes.width = guides.scale_m.width;
    planes.height = guides.scale_m.height;
    const std::size_t count =
        std::size_t(planes.width) * std::size_t(planes.height) + detail::kRatioPlaneSlack;
    for (std::vector<float> *v : {&planes.px, &planes.py, &planes.pz, &planes.nx, &planes.ny, &planes.nz,
                                  &planes.plane_m, &planes.inv_scale, &planes.minus_half_inv_sigma_sq})
        v->assign(count, 0.0f);
    planes.radius_px.assign(count, 0);
    parallel_for_rows(planes.height, [&](int y) {
        for (int x = 0; x < planes.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(planes.width) + std::size_t(x);
            const float p[3] = {guides.position[0](x, y), guides.position[1](x, y), guides.position[2](x, y)};
            float n[3] = {guides.normal[0](x, y), guides.normal[1](x, y), guides.normal[2](x, y)};
            const float scale = guides.scale_m(x, y);
            const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(scale > 0) || !std::isfinite(scale) || !std::isfinite(p[0] + p[1] + p[2]) ||
                !(length > 0) || !std::isfinite(length))
                continue;
            for (int c = 0; c < 3; ++c) n[c] /= length;
            planes.px[i] = p[0];
            planes.py[i] = p[1];
            planes.pz[i] = p[2];
            planes.nx[i] = n[0];
            planes.ny[i] = n[1];
            planes.nz[i] = n[2];
            planes.plane_m[i] = n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
            planes.inv_scale[i] = 1.0f / (settings.plane_sigma * scale);
            set_reach(planes, i, sigma_px(x, y), settings.cutoff_sigmas);
        }
    });
    return planes;
}

void check_inputs(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                  const RatioBilateralSettings &settings, const std::vector<std::vector<float>> &sources) {
    if (!(settings.plane_sigma > 0) || !(settings.cutoff_sigmas > 0))
        throw Error("ratio bilateral: plane sigma and cut-off must be > 0");
    if (sources.empty() || sources.size() > std::size_t(detail::kRatioMaxPlanes))
        throw Error("ratio bilateral: 1 to 8 planes per pass");
    const int width = guides.scale_m.width, height = guides.scale_m.height;
    if (!sigma_px.valid() || sigma_px.width != width || sigma_px.height != height)
        throw Error("ratio bilateral: sigma is missing or has another size");
    for (const std::vector<float> &s : sources)
        if (s.size() != std::size_t(width) * std::size_t(height))
            throw Error("ratio bilateral: a source has another size");
}

/// Columns and rows of the vertical pass's tiles: a tile's window of rows
/// (up to 2 reach + 1 of them, 4 guide planes and the sources) stays in the
/// core's cache from one row to the next at any image width.
constexpr int kStripPixels = 256, kTileRows = 64;

/// The horizontal pass into planes of the sources' size; then the vertical
/// pass, which hands each pixel's filtered values to `sink(x, y, values)`.
/// Each pixel sums its taps in a fixed order, so the result does not depend
/// on the thread count (nor on the instruction set: ratio_rows.cpp).
template <typename Sink>
void two_passes(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                const RatioBilateralSettings &settings, const std::vector<std::vector<float>> &sources,
                const Sink &sink) {
    check_inputs(guides, sigma_px, settings, sources);
    const RatioBilateralPlanes planes = planes_from(guides, sigma_px, settings);
    const int width = planes.width, height = planes.height, k_count = int(sources.size());
    const std::size_t count = std::size_t(width) * std::size_t(height);
    // The planes one after another, slack after the last (the vertical pass's vectors).
    std::vector<float> horizontal(count * std::size_t(k_count) + detail::kRatioPlaneSlack);
    detail::RatioBilateralSweep along_x, along_y;
    along_x.planes = along_y.planes = &planes;
    along_x.count = along_y.count = k_count;
    for (int k = 0; k < k_count; ++k) {
        along_x.source[k] = sources[std::size_t(k)].data();
        along_x.output[k] = &horizontal[std::size_t(k) * count];
        along_y.source[k] = along_x.output[k];
    }
    parallel_for_rows(height, [&](int y) { detail::ratio_bilateral_row_x(along_x, y); });
    const int strips = (width + kStripPixels - 1) / kStripPixels;
    parallel_for_tiles(height, kTileRows, strips, 1, [&](const TileRange &tile) {
        float values[kStripPixels * detail::kRatioMaxPlanes];
        for (int strip = tile.col_begin; strip != tile.col_end; ++strip) {
            const int x_begin = strip * kStripPixels, x_end = std::min(width, x_begin + kStripPixels);
            for (int y = tile.row_begin; y != tile.row_end; ++y) {
                detail::ratio_bilateral_row_y(along_y, y, x_begin, x_end, values);
                for (int x = x_begin; x < x_end; ++x)
                    sink(x, y, &values[std::size_t(x - x_begin) * std::size_t(k_count)]);
            }
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
