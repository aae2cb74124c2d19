#include "aaf/core/kernels/gather.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "aaf/core/kernels/fast_exp.h"
#include "aaf/core/kernels/gather_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

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
    const float inv_two_sigma_sq_n = Sheared ? g.inv_two_sigma_sq_n[c] : 0.0f;
    const int x_begin = std::max(0, x - reach_x), x_end = std::min(g.width, x + reach_x + 1);
    const int y_begin = std::max(0, y - reach_y), y_end = std::min(g.height, y + reach_y + 1);

    float sum[K][kLanes] = {}, weight_sum[kLanes] = {};
    auto accumulate = [&](std::size_t t, int lane) {
        const float cos_angle = nx * g.normal_x[t] + ny * g.normal_y[t] + nz * g.normal_z[t];
        const float accepted = float(g.object_id[t] == id) * float(cos_angle >= cos_threshold);
        float du = g.coord_u_m[t] - u, dv = g.coord_v_m[t] - v, normal_term = 0.0f;
        if (Sheared) {
            const float dn = g.coord_n_m[t] - n;
            du -= shear_u * dn;
            dv -= shear_v * dn;
            normal_term = dn * dn * inv_two_sigma_sq_n;
        }
        const float exponent = anisotropic ? -(du * du * inv_u + dv * dv * inv_v)
                                           : -(du * du + dv * dv) * inv_two_sigma_sq;  // AAF Eq. 11
        const float weight = accepted * fast_exp_nonpositive(exponent - normal_term);
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
                if (mod_u.inv_two_sigma_sq.valid())
                    modulation.inv_two_sigma_sq_u = mod_u.inv_two_sigma_sq(x, y);
                if (mod_v.inv_two_sigma_sq.valid())
                    modulation.inv_two_sigma_sq_v = mod_v.inv_two_sigma_sq(x, y);
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

/// The planes one gather reads and writes: contiguous, row-major, the
/// guides' size. Views that already are such planes are used in place; the
/// others go through uninitialised scratch planes (copied in, or out by
/// finish()).
class SweepPlanes {
  public:
    std::vector<const float *> source;
    std::vector<float *> output;

    /// `outputs_may_alias`: the caller reads every source before it writes
    /// any output (the separable gather's first pass), so an output may
    /// share memory with a source.
    SweepPlanes(const std::vector<ConstPlaneView> &sources, const std::vector<PlaneView> &outputs,
                bool outputs_may_alias) {
        for (const ConstPlaneView &view : sources) {
            if (contiguous(view)) {
                source.push_back(view.data);
                continue;
            }
            float *copy = scratch(view.width, view.height);
            for (int y = 0; y < view.height; ++y)
                for (int x = 0; x < view.width; ++x)
                    copy[std::size_t(y) * std::size_t(view.width) + x] = view(x, y);
            source.push_back(copy);
        }
        for (const PlaneView &view : outputs) {
            bool in_place = contiguous(view);
            for (std::size_t k = 0; in_place && !outputs_may_alias && k < sources.size(); ++k)
                in_place = !overlap(view, sources[k]);
            output.push_back(in_place ? view.data : scratch(view.width, view.height));
        }
    }
    /// A guide-sized plane of scratch, not initialised.
    float *scratch(int width, int height) {
        storage_.push_back(make_frame_scratch(std::size_t(width) * std::size_t(height)));
        return storage_.back().get();
    }
    /// Copies the outputs that went through scratch into their views.
    void finish(const std::vector<PlaneView> &outputs) const {
        for (std::size_t k = 0; k < outputs.size(); ++k) {
            if (output[k] == outputs[k].data) continue;
            for (int y = 0; y < outputs[k].height; ++y)
                for (int x = 0; x < outputs[k].width; ++x)
                    outputs[k](x, y) =
                        output[k][std::size_t(y) * std::size_t(outputs[k].width) + std::size_t(x)];
        }
    }

  private:
    template <typename T>
    static bool contiguous(const BasicPlaneView<T> &view) {
        return view.pixel_stride == 1 && view.row_stride == view.width;
    }
    /// Whether the memory spans of two views meet (conservatively, from the first to the last element).
    static bool overlap(const PlaneView &a, const ConstPlaneView &b) {
        auto span = [](const float *data, int width, int height, std::ptrdiff_t pixel, std::ptrdiff_t row) {
            const std::ptrdiff_t last = std::ptrdiff_t(height - 1) * row + std::ptrdiff_t(width - 1) * pixel;
            const float *end = data + last;
            return std::make_pair(std::min(data, end, std::less<>()), std::max(data, end, std::less<>()));
        };
        const auto sa = span(a.data, a.width, a.height, a.pixel_stride, a.row_stride);
        const auto sb = span(b.data, b.width, b.height, b.pixel_stride, b.row_stride);
        return !(std::less<>()(sa.second, sb.first) || std::less<>()(sb.second, sa.first));
    }
    std::vector<FrameScratch> storage_;
};

/// The sweep of `request` (modulated or not), kMaxChannelsPerSweep channels at a time.
template <bool Modulated>
void sweep_channels(const GatherSweepRequest &request) {
    const GatherGuides &g = *request.guides;
    const AxisModulation none;
    const AxisModulation &mod_u = Modulated ? *request.modulation_u : none;
    const AxisModulation &mod_v = Modulated ? *request.modulation_v : none;
    for (std::size_t first = 0; first < request.channels; first += kMaxChannelsPerSweep) {
        const std::size_t count = std::min<std::size_t>(kMaxChannelsPerSweep, request.channels - first);
        if (!Modulated) {
            // The SIMD rows (gather_rows.h): the same bits as gather_sweep's loops.
            detail::GatherSweep sweep;
            sweep.guides = &g;
            sweep.cos_threshold = request.cos_threshold;
            sweep.symmetric_borders = request.symmetric_borders;
            sweep.along_x = request.along_x;
            sweep.along_y = request.along_y;
            sweep.channels = int(count);
            for (std::size_t k = 0; k < count; ++k) {
                sweep.source[k] = request.sources[first + k];
                sweep.output[k] = request.outputs[first + k];
            }
            detail::gather_rows_tiled(sweep);
            continue;
        }
        auto run = [&](auto channels) {
            constexpr int K = decltype(channels)::value;
            Planes<K> planes;
            for (int k = 0; k < K; ++k) {
                planes.source[k] = request.sources[first + k];
                planes.output[k] = request.outputs[first + k];
            }
            gather_sweep<K, Modulated>(g, request.cos_threshold, request.symmetric_borders, planes,
                                       request.along_x, request.along_y, mod_u, mod_v, request.normalise);
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

class CpuGatherBackend final : public GatherBackend {
  public:
    void sweep(const GatherSweepRequest &request) const override {
        if (request.modulation_u || request.modulation_v)
            sweep_channels<true>(request);
        else
            sweep_channels<false>(request);
    }
};

/// Hands one sweep of `sources` into `outputs` to `settings`' backend.
void run_sweep(const GatherGuides &g, const GatherSettings &settings, float cos_threshold,
               const std::vector<const float *> &sources, const std::vector<float *> &outputs, bool along_x,
               bool along_y, const AxisModulation *mod_u = nullptr, const AxisModulation *mod_v = nullptr,
               bool normalise = true) {
    GatherSweepRequest request;
    request.guides = &g;
    request.cos_threshold = cos_threshold;
    request.symmetric_borders = settings.symmetric_borders;
    request.along_x = along_x;
    request.along_y = along_y;
    request.modulation_u = mod_u;
    request.modulation_v = mod_v;
    request.normalise = normalise;
    request.channels = sources.size();
    request.sources = sources.data();
    request.outputs = outputs.data();
    (settings.backend ? *settings.backend : cpu_gather_backend()).sweep(request);
}

void check_guides(const GatherGuides &g) {
    const std::size_t count = std::size_t(g.width) * std::size_t(g.height);
    for (const FramePlane<float> *plane : {&g.coord_u_m, &g.coord_v_m, &g.normal_x, &g.normal_y, &g.normal_z,
                                           &g.object_id, &g.inv_two_sigma_sq})
        if (plane->size() != count) throw Error("gather guides: a plane does not match the guides' size");
    if (!g.inv_two_sigma_sq_v.empty() && g.inv_two_sigma_sq_v.size() != count)
        throw Error("gather guides: the v width plane must match the guides' size or be empty");
    for (const FramePlane<float> *plane : {&g.coord_n_m, &g.shear_u, &g.shear_v, &g.inv_two_sigma_sq_n})
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

float cos_threshold_of(const GatherSettings &settings) {
    // Normals are unit, so their dot product is the cosine; no acos is needed.
    return std::cos(settings.normal_threshold_deg * kPi / 180.0f);
}

}  // namespace

const GatherBackend &cpu_gather_backend() {
    static const CpuGatherBackend backend;
    return backend;
}

void GatherGuides::resize(int new_width, int new_height) {
    width = new_width;
    height = new_height;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    for (FramePlane<float> *plane :
         {&coord_u_m, &coord_v_m, &normal_x, &normal_y, &normal_z, &object_id, &inv_two_sigma_sq})
        plane->assign(count, 0.0f);
    radius_px.assign(count, 0);
}

void GatherGuides::allocate(int new_width, int new_height) {
    width = new_width;
    height = new_height;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    for (FramePlane<float> *plane :
         {&coord_u_m, &coord_v_m, &normal_x, &normal_y, &normal_z, &object_id, &inv_two_sigma_sq}) {
        plane->clear();
        plane->resize(count);
    }
    radius_px.clear();
    radius_px.resize(count);
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
    if (settings.mode == GatherMode::Separable) {
        // w(x_ij - x_kl) = w(x_ij - x_kj) w(x_kj - x_kl) (AAF Sec. 6): gather
        // along columns into (k, j), then along the row into (i, j). The
        // vertical pass keeps neighbouring pixels of a row in the SIMD lanes
        // and loads the taps' rows contiguously, so no transpose is needed.
        // It reads every source before the second pass writes an output.
        SweepPlanes planes(sources, outputs, true);
        std::vector<float *> vertical(sources.size());
        for (float *&plane : vertical) plane = planes.scratch(guides.width, guides.height);
        run_sweep(guides, settings, cos_threshold, planes.source, vertical, false, true);
        run_sweep(guides, settings, cos_threshold,
                  std::vector<const float *>(vertical.begin(), vertical.end()), planes.output, true, false);
        planes.finish(outputs);
    } else {
        SweepPlanes planes(sources, outputs, false);
        // AAF Eq. 10 directly
        run_sweep(guides, settings, cos_threshold, planes.source, planes.output, true, true);
        planes.finish(outputs);
    }
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
    SweepPlanes planes(sources, outputs, false);
    run_sweep(guides, settings, cos_threshold_of(settings), planes.source, planes.output, true, true,
              &along_u, &along_v, normalisation == GatherNormalisation::WeightSum);
    planes.finish(outputs);
}

}  // namespace aaf
