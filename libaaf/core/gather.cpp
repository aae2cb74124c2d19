#include "aaf/core/gather.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "aaf/core/error.h"
#include "aaf/core/fast_exp.h"
#include "aaf/core/gather_rows.h"
#include "aaf/core/parallel.h"

namespace aaf {

namespace {

constexpr float kPi = 3.14159265358979323846f;

/// Taps accumulated in kLanes interleaved partial sums: a fixed summation
/// order (so results do not depend on threads or build flags) that the
/// compiler can still map onto SIMD lanes.
constexpr int kLanes = 8;
/// Channels gathered per sweep over the taps; more are done in further sweeps
/// with the same weights.
constexpr int kMaxChannelsPerSweep = detail::kMaxGatherChannels;

/// The tap weight's modulation m_u(du) m_v(dv) at one centre pixel.
struct PixelModulation {
    AxisModulation::Kind kind_u = AxisModulation::Kind::None, kind_v = AxisModulation::Kind::None;
    float omega_u = 0, omega_v = 0;
    /// Per-axis Gaussian widths (1 / (2 sigma^2)); negative = the guides' isotropic one.
    float inv_two_sigma_sq_u = -1, inv_two_sigma_sq_v = -1;

    static float factor(AxisModulation::Kind kind, float omega, float delta) {
        switch (kind) {
            case AxisModulation::Kind::Cos:
                return std::cos(omega * delta);
            case AxisModulation::Kind::NegSin:
                return -std::sin(omega * delta);
            default:
                return 1.0f;
        }
    }
    float operator()(float du, float dv) const {
        return factor(kind_u, omega_u, du) * factor(kind_v, omega_v, dv);
    }
};

/// Where one sweep reads and writes: K sources and outputs as raw planes.
template <int K>
struct Planes {
    const float *source[K];
    float *output[K];
};

/// Gathers pixel (x, y) over the taps |ox| <= reach_x, |oy| <= reach_y into
/// the K outputs. `Modulated` adds the per-tap factor and, with `normalise`
/// false, leaves the sums unnormalised.
template <int K, bool Modulated, bool Sheared>
void gather_pixel(const GatherGuides &g, float cos_threshold, const Planes<K> &planes, int x, int y,
                  int reach_x, int reach_y, const PixelModulation &modulation, bool normalise) {
    const std::size_t c = g.index(x, y);
    const float u = g.coord_u_m[c], v = g.coord_v_m[c], id = g.object_id[c];
    const float nx = g.normal_x[c], ny = g.normal_y[c], nz = g.normal_z[c];
    const float inv_two_sigma_sq = g.inv_two_sigma_sq[c];
    const float guide_inv_v = g.anisotropic() ? g.inv_two_sigma_sq_v[c] : inv_two_sigma_sq;
    const bool anisotropic =
        g.anisotropic() ||
        (Modulated && (modulation.inv_two_sigma_sq_u >= 0 || modulation.inv_two_sigma_sq_v >= 0));
    const float inv_u = modulation.inv_two_sigma_sq_u >= 0 ? modulation.inv_two_sigma_sq_u : inv_two_sigma_sq;
    const float inv_v = modulation.inv_two_sigma_sq_v >= 0 ? modulation.inv_two_sigma_sq_v : guide_inv_v;
    // GatherGuides::shear_u/v: the tap's offset along the third axis slides it
    // along the centre's own direction onto the centre's plane.
    const float n = Sheared ? g.coord_n_m[c] : 0.0f;
    const float shear_u = Sheared ? g.shear_u[c] : 0.0f, shear_v = Sheared ? g.shear_v[c] : 0.0f;
    const int x_begin = std::max(0, x - reach_x), x_end = std::min(g.width, x + reach_x + 1);
    const int y_begin = std::max(0, y - reach_y), y_end = std::min(g.height, y + reach_y + 1);

    float sum[K][kLanes] = {}, weight_sum[kLanes] = {};
    auto accumulate = [&](std::size_t t, int lane) {
        const float cos_angle = nx * g.normal_x[t] + ny * g.normal_y[t] + nz * g.normal_z[t];
        const float accepted = float(g.object_id[t] == id) * float(cos_angle >= cos_threshold);
        float du = g.coord_u_m[t] - u, dv = g.coord_v_m[t] - v;
        if (Sheared) {
            const float dn = g.coord_n_m[t] - n;
            du -= shear_u * dn;
            dv -= shear_v * dn;
        }
        const float weight =
            anisotropic ? accepted * fast_exp_nonpositive(-(du * du * inv_u + dv * dv * inv_v))
                      : accepted * fast_exp_nonpositive(-(du * du + dv * dv) * inv_two_sigma_sq);  // AAF Eq. 11
        weight_sum[lane] += weight;
        const float modulated = Modulated ? weight * modulation(du, dv) : weight;
        for (int k = 0; k < K; ++k) sum[k][lane] += modulated * planes.source[k][t];
    };
    for (int ty = y_begin; ty < y_end; ++ty) {
        const std::size_t row = std::size_t(ty) * std::size_t(g.width);
        int tx = x_begin;
        for (; tx + kLanes <= x_end; tx += kLanes)
            for (int lane = 0; lane < kLanes; ++lane) accumulate(row + std::size_t(tx + lane), lane);
        for (int lane = 0; tx < x_end; ++tx, ++lane) accumulate(row + std::size_t(tx), lane);
    }
    float total[K] = {}, total_weight = 0;
    for (int lane = 0; lane < kLanes; ++lane) {
        for (int k = 0; k < K; ++k) total[k] += sum[k][lane];
        total_weight += weight_sum[lane];
    }
    // The centre always counts: a NaN or zero normal fails its own test, so
    // it is added back with weight 1 (and modulation m(0, 0)).
    const bool centre_counted = (nx * nx + ny * ny + nz * nz) >= cos_threshold && id == id;
    if (!centre_counted) {
        const float centre_factor = Modulated ? modulation(0.0f, 0.0f) : 1.0f;
        for (int k = 0; k < K; ++k) total[k] += centre_factor * planes.source[k][c];
        total_weight += 1.0f;
    }
    for (int k = 0; k < K; ++k) planes.output[k][c] = normalise ? total[k] / total_weight : total[k];
}

/// One gather over the image along the enabled axes, each pixel within its
/// own radius; pixels with radius 0 copy their source. Rows run in parallel;
/// every pixel's sums have a fixed order, so threads cannot change the result.
template <int K, bool Modulated>
void gather_sweep(const GatherGuides &g, float cos_threshold, bool symmetric_borders, const Planes<K> &planes,
                  bool along_x, bool along_y, const AxisModulation &mod_u, const AxisModulation &mod_v,
                  bool normalise) {
    parallel_for_rows(g.height, [&](int y) {
        for (int x = 0; x < g.width; ++x) {
            const std::size_t c = g.index(x, y);
            const int radius = g.radius_px[c];
            if (radius == 0) {
                for (int k = 0; k < K; ++k) planes.output[k][c] = planes.source[k][c];
                continue;
            }
            PixelModulation modulation;
            if (Modulated) {
                modulation.kind_u = mod_u.kind;
                modulation.kind_v = mod_v.kind;
                if (mod_u.kind != AxisModulation::Kind::None)
                    modulation.omega_u = mod_u.omega_rad_per_m(x, y);
                if (mod_v.kind != AxisModulation::Kind::None)
                    modulation.omega_v = mod_v.omega_rad_per_m(x, y);
                if (mod_u.inv_two_sigma_sq.valid()) modulation.inv_two_sigma_sq_u = mod_u.inv_two_sigma_sq(x, y);
                if (mod_v.inv_two_sigma_sq.valid()) modulation.inv_two_sigma_sq_v = mod_v.inv_two_sigma_sq(x, y);
            }
            int reach_x = along_x ? radius : 0, reach_y = along_y ? radius : 0;
            if (symmetric_borders) {
                // A window cut by the image edge on one side only weighs the
                // interior: on a gradient that biases the result (AAF Sec. 6
                // does not say); cutting the other side to match keeps it centred.
                reach_x = std::min({reach_x, x, g.width - 1 - x});
                reach_y = std::min({reach_y, y, g.height - 1 - y});
            }
            if (g.sheared())
                gather_pixel<K, Modulated, true>(g, cos_threshold, planes, x, y, reach_x, reach_y, modulation,
                                                 normalise);
            else
                gather_pixel<K, Modulated, false>(g, cos_threshold, planes, x, y, reach_x, reach_y,
                                                  modulation, normalise);
        }
    });
}

/// Packed planes: the gather works on contiguous row-major planes of the guides' size.
using PackedPlanes = std::vector<std::vector<float>>;

PackedPlanes pack(const std::vector<ConstPlaneView> &views) {
    PackedPlanes planes(views.size());
    for (std::size_t k = 0; k < views.size(); ++k) {
        const ConstPlaneView &view = views[k];
        planes[k].resize(std::size_t(view.width) * std::size_t(view.height));
        for (int y = 0; y < view.height; ++y)
            for (int x = 0; x < view.width; ++x)
                planes[k][std::size_t(y) * std::size_t(view.width) + x] = view(x, y);
    }
    return planes;
}

/// Writes the transpose of a row-major width x height plane into `out`
/// (height x width) in 32 x 32 blocks, so that both sides stay in cache;
/// block rows in parallel (each element is written once: no ordering issue).
template <typename T>
void transpose_into(const T *plane, int width, int height, T *out) {
    constexpr int kBlock = 32;
    parallel_for_rows((height + kBlock - 1) / kBlock, [&](int block_row) {
        const int y0 = block_row * kBlock, y1 = std::min(height, y0 + kBlock);
        for (int x0 = 0; x0 < width; x0 += kBlock) {
            const int x1 = std::min(width, x0 + kBlock);
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x)
                    out[std::size_t(x) * std::size_t(height) + std::size_t(y)] =
                        plane[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        }
    });
}

std::vector<float> transposed(const std::vector<float> &plane, int width, int height) {
    std::vector<float> out(plane.size());
    transpose_into(plane.data(), width, height, out.data());
    return out;
}

/// Runs gather_sweep over all channels, kMaxChannelsPerSweep at a time.
template <bool Modulated>
void sweep_all(const GatherGuides &g, float cos_threshold, bool symmetric_borders,
               const PackedPlanes &sources, PackedPlanes &outputs, bool along_x, bool along_y,
               const AxisModulation &mod_u = {}, const AxisModulation &mod_v = {}, bool normalise = true) {
    for (std::size_t first = 0; first < sources.size(); first += kMaxChannelsPerSweep) {
        const std::size_t count = std::min<std::size_t>(kMaxChannelsPerSweep, sources.size() - first);
        if (!Modulated) {
            // The SIMD rows (gather_rows.h): the same bits as gather_sweep's loops.
            detail::GatherSweep sweep;
            sweep.guides = &g;
            sweep.cos_threshold = cos_threshold;
            sweep.symmetric_borders = symmetric_borders;
            sweep.along_x = along_x;
            sweep.along_y = along_y;
            sweep.channels = int(count);
            for (std::size_t k = 0; k < count; ++k) {
                sweep.source[k] = sources[first + k].data();
                sweep.output[k] = outputs[first + k].data();
            }
            parallel_for_rows(g.height, [&](int y) { detail::gather_row(sweep, y); });
            continue;
        }
        auto run = [&](auto channels) {
            constexpr int K = decltype(channels)::value;
            Planes<K> planes;
            for (int k = 0; k < K; ++k) {
                planes.source[k] = sources[first + k].data();
                planes.output[k] = outputs[first + k].data();
            }
            gather_sweep<K, Modulated>(g, cos_threshold, symmetric_borders, planes, along_x, along_y, mod_u,
                                       mod_v, normalise);
        };
        switch (count) {
            case 1:
                run(std::integral_constant<int, 1>{});
                break;
            case 2:
                run(std::integral_constant<int, 2>{});
                break;
            case 3:
                run(std::integral_constant<int, 3>{});
                break;
            default:
                run(std::integral_constant<int, 4>{});
                break;
        }
    }
}

void check_guides(const GatherGuides &g) {
    const std::size_t count = std::size_t(g.width) * std::size_t(g.height);
    for (const std::vector<float> *plane : {&g.coord_u_m, &g.coord_v_m, &g.normal_x, &g.normal_y, &g.normal_z,
                                            &g.object_id, &g.inv_two_sigma_sq})
        if (plane->size() != count) throw Error("gather guides: a plane does not match the guides' size");
    if (!g.inv_two_sigma_sq_v.empty() && g.inv_two_sigma_sq_v.size() != count)
        throw Error("gather guides: the v width plane must match the guides' size or be empty");
    for (const std::vector<float> *plane : {&g.coord_n_m, &g.shear_u, &g.shear_v})
        if (plane->size() != (g.sheared() ? count : 0))
            throw Error("gather guides: the shear planes must all match the guides' size or all be empty");
    if (g.radius_px.size() != count)
        throw Error("gather guides: the radius plane does not match the guides' size");
}

void check_views(const GatherGuides &g, const std::vector<ConstPlaneView> &sources,
                 const std::vector<PlaneView> &outputs) {
    if (sources.size() != outputs.size()) throw Error("gather: as many outputs as sources are needed");
    auto fits = [&](int width, int height, bool valid) {
        return valid && width == g.width && height == g.height;
    };
    for (const ConstPlaneView &s : sources)
        if (!fits(s.width, s.height, s.valid()))
            throw Error("gather: a source is missing or has another size");
    for (const PlaneView &o : outputs)
        if (!fits(o.width, o.height, o.valid()))
            throw Error("gather: an output is missing or has another size");
}

void unpack(const PackedPlanes &planes, const std::vector<PlaneView> &outputs) {
    for (std::size_t k = 0; k < outputs.size(); ++k)
        for (int y = 0; y < outputs[k].height; ++y)
            for (int x = 0; x < outputs[k].width; ++x)
                outputs[k](x, y) = planes[k][std::size_t(y) * std::size_t(outputs[k].width) + std::size_t(x)];
}

float cos_threshold_of(const GatherSettings &settings) {
    // Normals are unit, so their dot product is the cosine; no acos is needed.
    return std::cos(settings.normal_threshold_deg * kPi / 180.0f);
}

}  // namespace

void GatherGuides::resize(int new_width, int new_height) {
    width = new_width;
    height = new_height;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    for (std::vector<float> *plane :
         {&coord_u_m, &coord_v_m, &normal_x, &normal_y, &normal_z, &object_id, &inv_two_sigma_sq})
        plane->assign(count, 0.0f);
    radius_px.assign(count, 0);
}

GatherGuides GatherGuides::transposed() const {
    GatherGuides t;
    t.width = height;
    t.height = width;
    auto swap_axes = [&](const auto &plane, auto &out) {
        out.resize(plane.size());
        if (plane.empty()) return;  // an optional plane left out
        transpose_into(plane.data(), width, height, out.data());
    };
    swap_axes(coord_u_m, t.coord_u_m);
    swap_axes(coord_v_m, t.coord_v_m);
    swap_axes(normal_x, t.normal_x);
    swap_axes(normal_y, t.normal_y);
    swap_axes(normal_z, t.normal_z);
    swap_axes(object_id, t.object_id);
    swap_axes(inv_two_sigma_sq, t.inv_two_sigma_sq);
    swap_axes(inv_two_sigma_sq_v, t.inv_two_sigma_sq_v);
    swap_axes(coord_n_m, t.coord_n_m);
    swap_axes(shear_u, t.shear_u);
    swap_axes(shear_v, t.shear_v);
    swap_axes(radius_px, t.radius_px);
    return t;
}

void GatherSettings::validate() const {
    if (!(normal_threshold_deg >= 0 && normal_threshold_deg <= 180))
        throw Error("normal threshold must lie in [0, 180] degrees");
}

void gather(const GatherGuides &guides, const GatherSettings &settings,
            const std::vector<ConstPlaneView> &sources, const std::vector<PlaneView> &outputs) {
    settings.validate();
    check_guides(guides);
    check_views(guides, sources, outputs);
    const float cos_threshold = cos_threshold_of(settings);
    const int width = guides.width, height = guides.height;
    const PackedPlanes packed = pack(sources);
    PackedPlanes result(packed.size(), std::vector<float>(packed.empty() ? 0 : packed[0].size()));
    if (settings.mode == GatherMode::Separable) {
        // w(x_ij - x_kl) = w(x_ij - x_kj) w(x_kj - x_kl) (AAF Sec. 6): gather
        // along columns into (k, j), then along the row into (i, j). The
        // vertical pass runs on the transposed image, over contiguous taps.
        const GatherGuides guides_t = guides.transposed();
        PackedPlanes sources_t(packed.size()), vertical_t(packed.size());
        for (std::size_t k = 0; k < packed.size(); ++k) {
            sources_t[k] = transposed(packed[k], width, height);
            vertical_t[k].resize(packed[k].size());
        }
        sweep_all<false>(guides_t, cos_threshold, settings.symmetric_borders, sources_t, vertical_t, true,
                         false);
        for (std::size_t k = 0; k < packed.size(); ++k)
            sources_t[k] = transposed(vertical_t[k], height, width);
        sweep_all<false>(guides, cos_threshold, settings.symmetric_borders, sources_t, result, true, false);
    } else {
        sweep_all<false>(guides, cos_threshold, settings.symmetric_borders, packed, result, true,
                         true);  // AAF Eq. 10 directly
    }
    unpack(result, outputs);
}

void gather_modulated(const GatherGuides &guides, const GatherSettings &settings,
                      const std::vector<ConstPlaneView> &sources, const std::vector<PlaneView> &outputs,
                      const AxisModulation &along_u, const AxisModulation &along_v,
                      GatherNormalisation normalisation) {
    settings.validate();
    check_guides(guides);
    check_views(guides, sources, outputs);
    for (const AxisModulation *m : {&along_u, &along_v})
        if (m->kind != AxisModulation::Kind::None &&
            !(m->omega_rad_per_m.valid() && m->omega_rad_per_m.width == guides.width &&
              m->omega_rad_per_m.height == guides.height))
            throw Error("modulated gather: a frequency plane is missing or has another size");
    for (const AxisModulation *m : {&along_u, &along_v})
        if (m->inv_two_sigma_sq.valid() &&
            !(m->inv_two_sigma_sq.width == guides.width && m->inv_two_sigma_sq.height == guides.height))
            throw Error("modulated gather: a per-axis width plane has another size");
    const PackedPlanes packed = pack(sources);
    PackedPlanes result(packed.size(), std::vector<float>(packed.empty() ? 0 : packed[0].size()));
    sweep_all<true>(guides, cos_threshold_of(settings), settings.symmetric_borders, packed, result, true,
                    true, along_u, along_v, normalisation == GatherNormalisation::WeightSum);
    unpack(result, outputs);
}

}  // namespace aaf
