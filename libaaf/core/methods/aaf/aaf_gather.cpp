// AAF's own gather (aaf_filter.h's aaf_gather()): the separable passes of
// AAF Sec. 6 on aaf_gather_rows.h's sweeps, with the object and normal tests
// skipped wherever a window's pixels share the centre's id and normal.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/methods/aaf/aaf_gather_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/frame_allocator.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

constexpr float kPi = 3.14159265358979323846f;
/// Columns per task of the vertical runs, and the vertical sweep's tiles
/// (gather_rows.h's kGatherTileRows x kGatherStripPixels: its window of rows
/// stays in the core's cache at any image width).
constexpr int kStripPixels = 256, kTileRows = 64;

/// AafSweep::uniform_reach along y, strips of columns in parallel.
void uniform_reach_along_y(const GatherGuides &g, float cos_threshold, std::int32_t *reach) {
    const int strips = (g.width + kStripPixels - 1) / kStripPixels;
    parallel_for_each_index(strips, [&](int strip) {
        detail::aaf_uniform_reach_along_y(g, cos_threshold, strip * kStripPixels,
                                          std::min(g.width, (strip + 1) * kStripPixels), reach);
    });
}

/// Runs `sweep` over the whole image, rows in parallel. A vertical sweep of
/// a wide image goes in tiles of rows by one strip of columns.
void run_sweep(const detail::AafSweep &sweep) {
    const int width = sweep.guides->width, height = sweep.guides->height;
    if (!sweep.along_y || width <= 2 * kStripPixels) {
        parallel_for_rows(height, [&](int y) { detail::aaf_gather_row(sweep, y, 0, width); });
        return;
    }
    const int strips = (width + kStripPixels - 1) / kStripPixels;
    parallel_for_tiles(height, kTileRows, strips, 1, [&](const TileRange &tile) {
        for (int strip = tile.col_begin; strip != tile.col_end; ++strip)
            for (int y = tile.row_begin; y != tile.row_end; ++y)
                detail::aaf_gather_row(sweep, y, strip * kStripPixels, (strip + 1) * kStripPixels);
    });
}

template <typename T>
bool contiguous(const BasicPlaneView<T> &view) {
    return view.pixel_stride == 1 && view.row_stride == view.width;
}

void check_views(const GatherGuides &g, const std::vector<ConstPlaneView> &sources,
                 const std::vector<PlaneView> &outputs) {
    const std::size_t count = std::size_t(g.width) * std::size_t(g.height);
    for (const FramePlane<float> *plane : {&g.coord_u_m, &g.coord_v_m, &g.normal_x, &g.normal_y, &g.normal_z,
                                           &g.object_id, &g.inv_two_sigma_sq})
        if (plane->size() != count || g.radius_px.size() != count)
            throw Error("AAF gather: a guide plane does not match the guides' size");
    if (sources.size() != outputs.size()) throw Error("AAF gather: as many outputs as sources are needed");
    for (const ConstPlaneView &s : sources)
        if (!s.valid() || s.width != g.width || s.height != g.height)
            throw Error("AAF gather: a source is missing or has another size");
    for (const PlaneView &o : outputs)
        if (!o.valid() || o.width != g.width || o.height != g.height)
            throw Error("AAF gather: an output is missing or has another size");
}

/// The separable gather of up to kMaxAafGatherChannels contiguous planes:
/// along y into scratch, then along x into `outputs` (which may alias `sources`).
void gather_channels(detail::AafSweep sweep, const std::int32_t *reach_y,
                     const std::vector<const float *> &sources, const std::vector<float *> &outputs) {
    const GatherGuides &g = *sweep.guides;
    const std::size_t count = std::size_t(g.width) * std::size_t(g.height);
    std::vector<FrameScratch> vertical;
    sweep.channels = int(sources.size());
    for (std::size_t k = 0; k < sources.size(); ++k) {
        vertical.push_back(make_frame_scratch(count));
        sweep.source[k] = sources[k];
        sweep.output[k] = vertical.back().get();
    }
    // w(x_ij - x_kl) = w(x_ij - x_kj) w(x_kj - x_kl) (AAF Sec. 6): along
    // columns into (k, j), then along the row into (i, j).
    sweep.along_y = true;
    sweep.uniform_reach = reach_y;
    run_sweep(sweep);
    for (std::size_t k = 0; k < sources.size(); ++k) {
        sweep.source[k] = vertical[k].get();
        sweep.output[k] = outputs[k];
    }
    sweep.along_y = false;
    sweep.uniform_reach = nullptr;
    run_sweep(sweep);
}

}  // namespace

void aaf_gather(const GatherGuides &guides, const AafParams &params,
                const std::vector<ConstPlaneView> &sources, const std::vector<PlaneView> &outputs) {
    const GatherSettings settings = aaf_gather_settings(params);
    if (settings.mode != GatherMode::Separable) return gather(guides, settings, sources, outputs);
    settings.validate();
    check_views(guides, sources, outputs);
    const std::size_t count = std::size_t(guides.width) * std::size_t(guides.height);
    if (count == 0) return;
    detail::AafSweep sweep;
    sweep.guides = &guides;
    // Normals are unit, so their dot product is the cosine; no acos is needed.
    sweep.cos_threshold = std::cos(settings.normal_threshold_deg * kPi / 180.0f);
    sweep.symmetric_borders = settings.symmetric_borders;
    FramePlane<std::int32_t> reach_y(count);
    uniform_reach_along_y(guides, sweep.cos_threshold, reach_y.data());
    // Views that are not contiguous planes go through scratch copies.
    std::vector<FrameScratch> copies;
    auto scratch = [&] {
        copies.push_back(make_frame_scratch(count));
        return copies.back().get();
    };
    for (std::size_t first = 0; first < sources.size(); first += detail::kMaxAafGatherChannels) {
        const std::size_t last = std::min(sources.size(), first + detail::kMaxAafGatherChannels);
        std::vector<const float *> in;
        std::vector<float *> out;
        for (std::size_t k = first; k < last; ++k) {
            const ConstPlaneView &s = sources[k];
            const PlaneView &o = outputs[k];
            float *copy = contiguous(s) ? nullptr : scratch();
            if (copy)
                parallel_for_rows(s.height, [&](int y) {
                    for (int x = 0; x < s.width; ++x) copy[guides.index(x, y)] = s(x, y);
                });
            in.push_back(copy ? copy : s.data);
            out.push_back(contiguous(o) ? o.data : scratch());
        }
        gather_channels(sweep, reach_y.data(), in, out);
        for (std::size_t k = first; k < last; ++k) {
            const PlaneView &o = outputs[k];
            if (out[k - first] == o.data) continue;
            const float *from = out[k - first];
            parallel_for_rows(o.height, [&](int y) {
                for (int x = 0; x < o.width; ++x) o(x, y) = from[guides.index(x, y)];
            });
        }
    }
}

}  // namespace aaf
