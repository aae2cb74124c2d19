// The separable joint bilateral of the ratio estimator (Heitz, Hill, McGuire
// 2018, Sec. 4.1): widths from the noise estimate, plane-distance weights.
#include "aaf/core/methods/ratio/ratio_bilateral.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "aaf/core/methods/ratio/ratio_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

using detail::RatioBilateralPlanes;

/// Pixels [x_begin, x_end) of row `y` of `view` packed: the view's own
/// when its pixels are adjacent, else a copy in `buffer` (x_end - x_begin floats).
const float *packed_span(ConstPlaneView view, int y, int x_begin, int x_end, float *buffer) {
    if (view.pixel_stride == 1) return &view(x_begin, y);
    for (int x = x_begin; x < x_end; ++x) buffer[x - x_begin] = view(x, y);
    return buffer;
}

/// The guides of pixels [x_begin, x_end) of row `y`, packed (strided views
/// copied into a per-thread buffer).
detail::RatioGuideRow guide_span(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                                 const RatioBilateralSettings &settings, int y, int x_begin, int x_end) {
    const std::size_t span = std::size_t(x_end - x_begin);
    thread_local std::vector<float> buffer;  // strided views' spans, packed
    buffer.resize(std::max(buffer.size(), span * 8));
    auto packed = [&](ConstPlaneView view, int slot) {
        return packed_span(view, y, x_begin, x_end, &buffer[std::size_t(slot) * span]);
    };
    detail::RatioGuideRow in;
    for (int c = 0; c < 3; ++c) {
        in.position[c] = packed(guides.position[std::size_t(c)], c);
        in.normal[c] = packed(guides.normal[std::size_t(c)], 3 + c);
    }
    in.scale_m = packed(guides.scale_m, 6);
    in.sigma_px = packed(sigma_px, 7);
    in.plane_sigma = settings.plane_sigma;
    in.cutoff_sigmas = settings.cutoff_sigmas;
    return in;
}

/// The per-pixel tap planes, sized; inv_scale 0 will mark "not a surface".
/// The horizontal pass writes each row just before it filters the row.
RatioBilateralPlanes sized_planes(const RatioBilateralGuides &guides) {
    RatioBilateralPlanes planes;
    const int width = guides.scale_m.width;
    planes.width = width;
    planes.height = guides.scale_m.height;
    const std::size_t count = std::size_t(width) * std::size_t(planes.height);
    auto size = [count](auto &plane) {
        plane.resize(count + detail::kRatioPlaneSlack);  // every pixel is written below
        std::fill(plane.begin() + std::ptrdiff_t(count), plane.end(), 0);
    };
    for (FramePlane<float> *plane : {&planes.px, &planes.py, &planes.pz, &planes.inv_scale}) size(*plane);
    size(planes.radius_px);
    return planes;
}

void check_inputs(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                  const RatioBilateralSettings &settings, const std::vector<ConstPlaneView> &sources) {
    if (!(settings.plane_sigma > 0) || !(settings.cutoff_sigmas > 0))
        throw Error("ratio bilateral: plane sigma and cut-off must be > 0");
    if (sources.empty() || sources.size() > std::size_t(detail::kRatioMaxPlanes))
        throw Error("ratio bilateral: 1 to 8 planes per pass");
    const int width = guides.scale_m.width, height = guides.scale_m.height;
    if (!sigma_px.valid() || sigma_px.width != width || sigma_px.height != height)
        throw Error("ratio bilateral: sigma is missing or has another size");
    for (const ConstPlaneView &s : sources)
        if (!s.valid() || s.width != width || s.height != height)
            throw Error("ratio bilateral: a source has another size");
}

/// Columns and rows of the vertical pass's tiles: a tile's window of rows
/// (up to 2 reach + 1 of them, 4 guide planes and the sources) stays in the
/// core's cache from one row to the next at any image width.
constexpr int kStripPixels = 256, kTileRows = 64;

/// The horizontal pass into planes of the sources' size; then the vertical
/// pass, which hands pixels [x_begin, x_end) of row y to `sink(y, x_begin,
/// x_end, values)`, values[k] their filtered plane k.
/// Each pixel sums its taps in a fixed order, so the result does not depend
/// on the thread count (nor on the instruction set: ratio_rows.cpp).
template <typename Sink>
void two_passes(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                const RatioBilateralSettings &settings, const std::vector<ConstPlaneView> &sources,
                const Sink &sink) {
    check_inputs(guides, sigma_px, settings, sources);
    RatioBilateralPlanes planes = sized_planes(guides);
    const int width = planes.width, height = planes.height, k_count = int(sources.size());
    const std::size_t count = std::size_t(width) * std::size_t(height);
    // One allocation per plane (frame-sized blocks are reused, much larger ones may not be).
    std::vector<FramePlane<float>> horizontal(static_cast<std::size_t>(k_count));
    for (FramePlane<float> &plane : horizontal) {
        plane.resize(count + detail::kRatioPlaneSlack);  // written in full below
        std::fill(plane.begin() + std::ptrdiff_t(count), plane.end(), 0.0f);
    }
    detail::RatioBilateralSweep along_x, along_y;
    along_x.planes = along_y.planes = &planes;
    along_x.count = along_y.count = k_count;
    for (int k = 0; k < k_count; ++k) {
        along_x.output[k] = horizontal[std::size_t(k)].data();
        along_y.source[k] = along_x.output[k];
    }
    parallel_for_rows(height, [&](int y) {
        thread_local std::vector<float> buffer;  // strided views' rows, packed
        buffer.resize(std::max(buffer.size(), std::size_t(width) * std::size_t(k_count)));
        const float *rows[detail::kRatioMaxPlanes];
        for (int k = 0; k < k_count; ++k)
            rows[k] = packed_span(sources[std::size_t(k)], y, 0, width,
                                  &buffer[std::size_t(k) * std::size_t(width)]);
        // The row's tap planes (the vertical pass reads them all), then its horizontal pass.
        const detail::RatioGuideRow row_guides = guide_span(guides, sigma_px, settings, y, 0, width);
        detail::ratio_planes_row(row_guides, y, planes);
        detail::ratio_bilateral_row_x(along_x, y, rows, row_guides);
    });
    const int strips = (width + kStripPixels - 1) / kStripPixels;
    parallel_for_tiles(height, kTileRows, strips, 1, [&](const TileRange &tile) {
        float values[kStripPixels * detail::kRatioMaxPlanes];
        for (int strip = tile.col_begin; strip != tile.col_end; ++strip) {
            const int x_begin = strip * kStripPixels, x_end = std::min(width, x_begin + kStripPixels);
            for (int y = tile.row_begin; y != tile.row_end; ++y) {
                detail::ratio_bilateral_row_y(along_y, y, x_begin, x_end, values,
                                              guide_span(guides, sigma_px, settings, y, x_begin, x_end));
                const float *planes_out[detail::kRatioMaxPlanes];
                for (int k = 0; k < k_count; ++k)
                    planes_out[k] = &values[std::size_t(k) * std::size_t(x_end - x_begin)];
                sink(y, x_begin, x_end, planes_out);
            }
        }
    });
}

}  // namespace

void ratio_bilateral_compose(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                             const RatioBilateralSettings &settings,
                             const std::vector<ConstPlaneView> &sources, const RatioComposition &composition,
                             const std::array<PlaneView, 3> &rgb, bool accumulate) {
    if (int(sources.size()) != composition.plane_count())
        throw Error("ratio bilateral: the sources do not match the estimator");
    for (const PlaneView &out : rgb)
        if (!out.valid() || out.width != sigma_px.width || out.height != sigma_px.height)
            throw Error("ratio bilateral: an output is missing or has another size");
    // Sec. 4.1 pass 4: the vertical pass writes the final radiance directly.
    two_passes(guides, sigma_px, settings, sources,
               [&](int y, int x_begin, int x_end, const float *const *values) {
                   composition.compose_row(y, x_begin, x_end, values, rgb, accumulate);
               });
}

void ratio_bilateral(const RatioBilateralGuides &guides, ConstPlaneView sigma_px,
                     const RatioBilateralSettings &settings, const std::vector<ConstPlaneView> &sources,
                     const std::vector<PlaneView> &outputs) {
    if (outputs.size() != sources.size()) throw Error("ratio bilateral: as many outputs as sources needed");
    for (const PlaneView &out : outputs)
        if (!out.valid() || out.width != sigma_px.width || out.height != sigma_px.height)
            throw Error("ratio bilateral: an output is missing or has another size");
    two_passes(guides, sigma_px, settings, sources,
               [&](int y, int x_begin, int x_end, const float *const *values) {
                   for (std::size_t k = 0; k < outputs.size(); ++k)
                       for (int x = x_begin; x < x_end; ++x) outputs[k](x, y) = values[k][x - x_begin];
               });
}

}  // namespace aaf
