#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "../path_sample.h"
#include "aaf/core/methods/maaf/maaf_roles.h"
#include "aaf/core/methods/maaf6/maaf6_components.h"
#include "aaf/core/methods/maaf6/maaf6_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"
#include "aov_groups.h"

namespace aaf::trace {

const ParameterDeclarations<Maaf6GroupSettings> &maaf6_group_parameters() {
    using P = Maaf6GroupSettings;
    static const auto declarations = std::move(ParameterDeclarations<P>("maaf6").parsed_text(
        "maaf6_effects", &P::effects, parse_maaf6_effects, maaf6_effects_name, "",
        "the effects its path samples trace, any of defocus,shadows,indirect"));
    return declarations;
}

namespace {

/// Random-number stream of the maaf6 path samples, apart from the render's own passes.
constexpr std::uint64_t kMaaf6Stream = 0x6d616166365f7374ull;
constexpr int kFirstPassSpp = 16;      ///< MAAF Sec. 6.2 "Sampling": 16 path samples
constexpr int kMaxExtraSpp = 100;      ///< MAAF Sec. 6.2: up to 100 more at the focal plane
constexpr int kPrefilterRadiusPx = 2;  ///< MAAF Sec. 6.2 "Pre-filtering": 5x5
constexpr float kNormalThresholdDeg = 20;
constexpr double kIndirectOmegaMax = 2.8;  ///< MAAF Sec. 3 (from AAF-GI), rad per unit tan
constexpr double kPixelBand = 2.0;         ///< Omega_x^max = 2 / pixel size, maaf.omegax's scale at s = 0

/// One path sample projected on its pixel's tangent frame.
struct Stored {
    float y1_direct, y2_direct;      ///< light point along t1, t2, metres from the light's centre
    float u1, u2;                    ///< lens point along t1, t2, metres from the lens centre
    float y1_indirect, y2_indirect;  ///< bounce direction, tan along t1, t2
    float direct[3], indirect[3];
    float direct_unoccluded_y;  ///< Rec. 709 luminance of the direct radiance with visibility 1
};

/// A pixel's raw first-pass slopes; min > max = none seen.
struct RawWedge {
    float direct_min = 1e30f, direct_max = -1e30f;
    float indirect_min = 1e30f, indirect_max = -1e30f;
    float u_min = 1e30f, u_max = -1e30f;
};

/// `s` on the tangent frame (t1, t2) of a receiver with normal `n`.
Stored project_sample(const PathSample &s, Vec3 t1, Vec3 t2, Vec3 n) {
    Stored stored{};
    stored.y1_direct = dot(s.light_offset_m, t1);
    stored.y2_direct = dot(s.light_offset_m, t2);
    stored.u1 = dot(s.lens_offset_m, t1);
    stored.u2 = dot(s.lens_offset_m, t2);
    const float cos_n = dot(s.bounce_direction, n);
    if (cos_n > 1e-3f) {  // the unit plane above the receiver (AAF-GI's parametrisation)
        stored.y1_indirect = dot(s.bounce_direction, t1) / cos_n;
        stored.y2_indirect = dot(s.bounce_direction, t2) / cos_n;
    }
    stored.direct_unoccluded_y =
        0.2126f * s.direct_unoccluded.x + 0.7152f * s.direct_unoccluded.y + 0.0722f * s.direct_unoccluded.z;
    for (int c = 0; c < 3; ++c) {
        stored.direct[c] = s.direct[c];
        stored.indirect[c] = s.indirect[c];
    }
    return stored;
}

/// Widens `w` to the slopes of a first-pass sample `s` that hit a surface.
void widen_raw_wedge(RawWedge &w, const PathSample &s, float focus_distance_m) {
    if (s.direct_slope >= 0) {
        w.direct_min = std::min(w.direct_min, s.direct_slope);
        w.direct_max = std::max(w.direct_max, s.direct_slope);
    }
    if (s.bounce_height_m > 0) {
        w.indirect_min = std::min(w.indirect_min, s.bounce_height_m);
        w.indirect_max = std::max(w.indirect_max, s.bounce_height_m);
    }
    const float u_slope = 1.0f - s.depth_m / focus_distance_m;  // s_u = 1 - z/F (methods/maaf6/README.md)
    w.u_min = std::min(w.u_min, u_slope);
    w.u_max = std::max(w.u_max, u_slope);
}

/// Every pixel's maaf6 path samples, projected on its tangent frame, and the
/// raw slopes of its first pass. Pixels may be traced concurrently: each call
/// touches only its own pixel's entries.
class Maaf6Samples {
  public:
    Maaf6Samples(const RenderState &state, unsigned effects)
        : samples(std::size_t(state.width) * std::size_t(state.height)),
          raw(samples.size()),
          state_(state),
          sampler_(state.scene, state.renderer->rays(), effects),
          t1_(samples.size()),
          t2_(samples.size()) {
        // Each pixel's tangent frame (maaf6_tangent_frame), from the central primary hit's normal.
        const LightPlane &light = state.scene.key_light();
        for (std::size_t i = 0; i < samples.size(); ++i)
            if (state.primaries[i].found)
                maaf6_tangent_frame(state.primaries[i].normal, light.axis_u, light.axis_v, t1_[i], t2_[i]);
    }

    /// Traces `n` samples of pass `pass` for pixel (x, y), index `i`; pass 0's give the raw slopes.
    void trace(std::size_t i, int x, int y, std::uint32_t pass, int n) {
        PixelRng rng(state_.seed ^ kMaaf6Stream, i, pass);
        const StratifiedGrid strata(std::uint32_t(std::max(1, n)));
        const std::uint32_t keys[4] = {rng.next_u32(), rng.next_u32(), rng.next_u32(), rng.next_u32()};
        for (int k = 0; k < n; ++k) {
            const PathSample s = sampler_.trace(x, y, numbers(rng, strata, keys, k, n));
            samples[i].push_back(project_sample(s, t1_[i], t2_[i], state_.primaries[i].normal));
            if (pass == 0 && s.hit) widen_raw_wedge(raw[i], s, state_.scene.camera.focus_distance_m);
        }
    }

    std::vector<std::vector<Stored>> samples;  ///< per pixel, in the order traced
    std::vector<RawWedge> raw;                 ///< per pixel, of its pass-0 samples

  private:
    /// The random numbers of sample `k` of `n`.
    static PathSampleNumbers numbers(PixelRng &rng, const StratifiedGrid &strata, const std::uint32_t keys[4],
                                     int k, int n) {
        PathSampleNumbers numbers;
        UnitPoint *points[4] = {&numbers.lens, &numbers.light, &numbers.bounce, &numbers.bounce_light};
        for (int d = 0; d < 4; ++d) {
            float a, b;
            rng.next_float2(a, b);
            // Each dimension pairs sample k with its own permutation of the strata: with
            // one shared order (a full grid is not permuted) the lens, light and bounce
            // points would share strata, a correlation that biases the product integral.
            const std::uint32_t index =
                d == 0 ? std::uint32_t(k) : permute_index(std::uint32_t(k), std::uint32_t(n), keys[d]);
            *points[d] = strata.point(index, keys[d], a, b);
        }
        return numbers;
    }

    const RenderState &state_;
    const PathSampler sampler_;
    std::vector<Vec3> t1_, t2_;
};

/// Every pixel's slopes after pre-filtering (-1 for none along y, 0 along u)
/// and its pixel band Omega_x^max.
struct PixelWedges {
    explicit PixelWedges(std::size_t count)
        : direct_min(count, -1),
          direct_max(count, -1),
          indirect_min(count, -1),
          indirect_max(count, -1),
          u_min(count, 0),
          u_max(count, 0),
          omega_x(count, 0) {}
    std::vector<float> direct_min, direct_max, indirect_min, indirect_max, u_min, u_max, omega_x;
};

/// MAAF Sec. 6.2 "Pre-filtering" of pixel (x, y), which has a central hit:
/// the raw slopes averaged over 5x5 (pixels with a central hit and a normal
/// within 20 degrees; the defocus slopes over every pixel with a hit).
void prefilter_pixel(const RenderState &state, const std::vector<RawWedge> &raw, int x, int y,
                     PixelWedges &wedges) {
    const int width = state.width, height = state.height;
    const float cos_threshold = std::cos(kNormalThresholdDeg * 3.14159265f / 180.0f);
    const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
    const PrimaryHit &centre = state.primaries[i];
    double sums[6] = {0, 0, 0, 0, 0, 0};
    int used_direct = 0, used_indirect = 0, used_u = 0;
    for (int ty = std::max(0, y - kPrefilterRadiusPx); ty <= std::min(height - 1, y + kPrefilterRadiusPx);
         ++ty)
        for (int tx = std::max(0, x - kPrefilterRadiusPx); tx <= std::min(width - 1, x + kPrefilterRadiusPx);
             ++tx) {
            const std::size_t t = std::size_t(ty) * std::size_t(width) + std::size_t(tx);
            const RawWedge &w = raw[t];
            if (w.u_min <= w.u_max) {
                sums[4] += w.u_min;
                sums[5] += w.u_max;
                ++used_u;
            }
            if (!state.primaries[t].found || dot(state.primaries[t].normal, centre.normal) < cos_threshold)
                continue;
            if (w.direct_min <= w.direct_max) {
                sums[0] += w.direct_min;
                sums[1] += w.direct_max;
                ++used_direct;
            }
            if (w.indirect_min <= w.indirect_max) {
                sums[2] += w.indirect_min;
                sums[3] += w.indirect_max;
                ++used_indirect;
            }
        }
    // The mean of the minima and, at least as large, of the maxima.
    auto mean = [&](int used, double lo_sum, double hi_sum, float &lo, float &hi) {
        if (used == 0) return;
        lo = float(lo_sum / used);
        hi = std::max(lo, float(hi_sum / used));
    };
    mean(used_direct, sums[0], sums[1], wedges.direct_min[i], wedges.direct_max[i]);
    mean(used_indirect, sums[2], sums[3], wedges.indirect_min[i], wedges.indirect_max[i]);
    mean(used_u, sums[4], sums[5], wedges.u_min[i], wedges.u_max[i]);
    wedges.omega_x[i] = float(kPixelBand / std::max(1e-9f, centre.pixel_size_m));
}

PixelWedges prefilter_wedges(const RenderState &state, const std::vector<RawWedge> &raw) {
    PixelWedges wedges(raw.size());
    parallel_for_rows(state.height, [&](int y) {
        for (int x = 0; x < state.width; ++x)
            if (state.primaries[std::size_t(y) * std::size_t(state.width) + std::size_t(x)].found)
                prefilter_pixel(state, raw, x, y, wedges);
    });
    return wedges;
}

/// The band-limits of a render (MAAF Sec. 3) and whether it traces a lens.
struct Bands {
    bool lens;
    double omega_u;       ///< 4 / A, L = A; 0 for a pinhole
    double omega_direct;  ///< 2 / sigma_y
};

/// Traces the rest of every pixel's samples, and the focal-plane pixels' extra ones.
void trace_remaining(const RenderState &state, Maaf6Samples &samples, const PixelWedges &wedges,
                     const Bands &bands, int first_spp) {
    const Camera &camera = state.scene.camera;
    parallel_for_rows(state.height, [&](int y) {
        for (int x = 0; x < state.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(state.width) + std::size_t(x);
            if (state.spp > first_spp) samples.trace(i, x, y, 1, state.spp - first_spp);
            if (bands.lens && state.primaries[i].found && wedges.u_min[i] * wedges.u_max[i] < 0) {
                // Stand-in for MYRD14 Sec. 7's rate (not among the shared papers): the box
                // spans the whole lens band, so the samples scale with the lens band's
                // periods across the aperture, (1 + A Omega_u^max / (2 pi))^2, capped at +100.
                const double scale =
                    1.0 + double(camera.aperture_radius_m) * bands.omega_u / (2.0 * 3.14159265358979);
                const int extra =
                    std::min(kMaxExtraSpp, int(std::ceil(state.spp * scale * scale)) - state.spp);
                samples.trace(i, x, y, 2, extra);
            }
        }
    });
}

/// The channels the group writes, and the beauty it replaces.
struct Maaf6Views {
    explicit Maaf6Views(AovSet &aovs)
        : direct(add_role_channels(aovs, roles::Maaf6Direct)),
          indirect(add_role_channels(aovs, roles::Maaf6Indirect)),
          direct_sums(add_role_channels(aovs, roles::Maaf6DirectSums)),
          direct_weights(add_role_channels(aovs, roles::Maaf6DirectWeights)),
          indirect_sums(add_role_channels(aovs, roles::Maaf6IndirectSums)),
          indirect_weights(add_role_channels(aovs, roles::Maaf6IndirectWeights)),
          wedge(add_role_channels(aovs, roles::Maaf6Wedge)),
          spp(add_role_channels(aovs, roles::Maaf6Spp)),
          beauty{aovs.channel("R"), aovs.channel("G"), aovs.channel("B")} {}
    std::vector<PlaneView> direct, indirect, direct_sums, direct_weights, indirect_sums, indirect_weights,
        wedge, spp;
    PlaneView beauty[3];
};

/// Pixel (x, y)'s mean direct and indirect radiance, their sum as the beauty, its wedge and sample count.
void write_pixel_means(const std::vector<Stored> &mine, const PixelWedges &wedges, std::size_t i, int x,
                       int y, const Maaf6Views &views) {
    const double n = mine.empty() ? 1.0 : double(mine.size());
    double mean_direct[3] = {0, 0, 0}, mean_indirect[3] = {0, 0, 0};
    for (const Stored &s : mine)
        for (int c = 0; c < 3; ++c) {
            mean_direct[c] += s.direct[c] / n;
            mean_indirect[c] += s.indirect[c] / n;
        }
    for (int c = 0; c < 3; ++c) {
        views.direct[std::size_t(c)](x, y) = float(mean_direct[c]);
        views.indirect[std::size_t(c)](x, y) = float(mean_indirect[c]);
        views.beauty[c](x, y) = float(mean_direct[c] + mean_indirect[c]);
    }
    const std::vector<float> *planes[7] = {&wedges.direct_min,   &wedges.direct_max, &wedges.indirect_min,
                                           &wedges.indirect_max, &wedges.u_min,      &wedges.u_max,
                                           &wedges.omega_x};
    for (std::size_t k = 0; k < 7; ++k) views.wedge[k](x, y) = (*planes[k])[i];
    views.spp[0](x, y) = float(mine.size());
}

/// The filter pairs of pixel `i`'s direct or indirect layer (its wedge's
/// MAAF Eq. 24 components); phases 0 for the background, where only the mean matters.
std::vector<Maaf6Component> layer_pairs(const RenderState &state, const PixelWedges &wedges,
                                        const Bands &bands, std::size_t i, bool is_direct) {
    if (!state.primaries[i].found) return std::vector<Maaf6Component>(std::size_t(kMaafContractPairs));
    Maaf6Wedge wedge;
    const float lo = is_direct ? wedges.direct_min[i] : wedges.indirect_min[i];
    const float hi = is_direct ? wedges.direct_max[i] : wedges.indirect_max[i];
    wedge.has_y = lo >= 0 && hi >= 0;
    wedge.y_min = wedge.has_y ? double(lo) : 0.0;
    wedge.y_max = wedge.has_y ? double(hi) : 0.0;
    wedge.omega_y_max = is_direct ? bands.omega_direct : kIndirectOmegaMax;
    wedge.has_u = bands.lens;
    wedge.u_min = double(wedges.u_min[i]);
    wedge.u_max = double(wedges.u_max[i]);
    wedge.omega_u_max = bands.omega_u;
    wedge.omega_x_max = double(wedges.omega_x[i]);
    return maaf6_pair_components(wedge, kMaafContractPairs);
}

/// MAAF Eq. 23: pixel (x, y)'s sums of one layer with its pixel's parameters;
/// `rgb` and `weight` are scratch of 3 * channels and channels entries.
void write_layer_sums(const std::vector<Stored> &mine, const std::vector<Maaf6Component> &pairs,
                      bool is_direct, int x, int y, const Maaf6Views &views, std::vector<double> &rgb,
                      std::vector<double> &weight) {
    std::fill(rgb.begin(), rgb.end(), 0.0);
    std::fill(weight.begin(), weight.end(), 0.0);
    const Maaf6SampleSide side(pairs);
    for (const Stored &s : mine)
        side.accumulate(is_direct ? s.y1_direct : s.y1_indirect, s.u1,
                        is_direct ? s.y2_direct : s.y2_indirect, s.u2, is_direct ? s.direct : s.indirect,
                        is_direct ? double(s.direct_unoccluded_y) : 1.0, rgb.data(), weight.data());
    const std::vector<PlaneView> &sums = is_direct ? views.direct_sums : views.indirect_sums;
    const std::vector<PlaneView> &weights = is_direct ? views.direct_weights : views.indirect_weights;
    for (std::size_t c = 0; c < weight.size(); ++c) {
        weights[c](x, y) = float(weight[c]);
        for (std::size_t k = 0; k < 3; ++k) sums[3 * c + k](x, y) = float(rgb[3 * c + k]);
    }
}

/// Writes every pixel's means, wedge, sample count and both layers' sums.
void write_channels(const RenderState &state, const Maaf6Samples &samples, const PixelWedges &wedges,
                    const Bands &bands, AovSet &aovs) {
    const Maaf6Views views(aovs);
    const std::size_t channels = std::size_t(maaf6_channel_count(kMaafContractPairs));
    parallel_for_rows(state.height, [&](int y) {
        std::vector<double> rgb(3 * channels), weight(channels);
        for (int x = 0; x < state.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(state.width) + std::size_t(x);
            const std::vector<Stored> &mine = samples.samples[i];
            write_pixel_means(mine, wedges, i, x, y, views);
            for (const bool is_direct : {true, false})
                write_layer_sums(mine, layer_pairs(state, wedges, bands, i, is_direct), is_direct, x, y,
                                 views, rgb, weight);
        }
    });
}

/// What the beauty holds once the group replaced it (aaf:beauty_effects).
std::string beauty_effects(unsigned effects, bool lens) {
    std::string text = "key_light";  // the path samples trace no other light
    text += (effects & kMaaf6Shadows) ? ",soft_shadows" : ",hard_shadows";
    if (lens) text += ",defocus";
    if (effects & kMaaf6Indirect) text += ",indirect";
    return text;
}

/// MAAF for combined effects (Sec. 6.2) in two passes: 16 path samples give
/// each pixel's slopes (direct, indirect, defocus), averaged over 5x5; pixels
/// whose defocus slopes straddle 0 (the focal-plane box) get extra samples;
/// then every sample is accumulated into the 6D product channels, direct and
/// indirect apart. The group traces its own path samples when it writes
/// (through the render's Renderer, as isg does); the render's beauty is
/// replaced by the mean of direct + indirect, and aaf:beauty_effects says so.
class Maaf6Group final : public AovAccumulator {
  public:
    AovGroupInfo info() const override {
        AovGroupInfo info = group_info(
            "maaf6",
            "maaf6.direct.*, maaf6.indirect.* (75 sums + 25 weights each, N = 3), maaf6 wedges, maaf6.spp; "
            "traces its own path samples (lens, area light, one diffuse bounce) and replaces R, G, B",
            roles());
        info.parameters = maaf6_group_parameters().infos();
        info.not_resumable_because = "they trace their own samples";
        return info;
    }
    std::vector<Role> roles() const override {
        return {roles::Maaf6Direct,        roles::Maaf6Indirect,     roles::Maaf6DirectSums,
                roles::Maaf6DirectWeights, roles::Maaf6IndirectSums, roles::Maaf6IndirectWeights,
                roles::Maaf6Wedge,         roles::Maaf6Spp};
    }

    /// The effects' names are parsed here, so that a bad list is refused before anything renders.
    void set_parameters(const ParameterSet &values) override {
        settings_ = maaf6_group_parameters().read(values);
    }

    void write(const RenderState &state, AovSet &aovs) const override {
        if (!state.renderer) throw Error("the maaf6 group needs the render's tracer");
        using Clock = std::chrono::steady_clock;
        const auto start = Clock::now();
        const Camera &camera = state.scene.camera;
        const unsigned effects = settings_.effects;
        const bool lens = (effects & kMaaf6Defocus) && camera.is_thin_lens();
        const Bands bands{lens, lens ? 4.0 / double(camera.aperture_radius_m) : 0.0,  // MAAF Sec. 3, L = A
                          2.0 / double(state.scene.key_light().sigma_m)};  // MAAF Sec. 3: 2 / sigma_y
        const int first_spp = std::min(kFirstPassSpp, state.spp);

        // MAAF Sec. 6.2 "Sampling": the first pass, then the rest and the focal plane's extra samples.
        Maaf6Samples samples(state, effects);
        parallel_for_rows(state.height, [&](int y) {
            for (int x = 0; x < state.width; ++x)
                samples.trace(std::size_t(y) * std::size_t(state.width) + std::size_t(x), x, y, 0, first_spp);
        });
        const PixelWedges wedges = prefilter_wedges(state, samples.raw);
        trace_remaining(state, samples, wedges, bands, first_spp);
        const double sampling_s = std::chrono::duration<double>(Clock::now() - start).count();

        const auto accumulate_start = Clock::now();
        write_channels(state, samples, wedges, bands, aovs);
        aovs.attributes[attr::kMaaf6Pairs] = kMaafContractPairs;
        aovs.attributes[attr::kMaaf6OmegaDirect] = float(bands.omega_direct);
        aovs.attributes[attr::kMaaf6OmegaIndirect] = float(kIndirectOmegaMax);
        aovs.attributes[attr::kMaaf6OmegaLens] = float(bands.omega_u);
        aovs.attributes[attr::kMaaf6Effects] = maaf6_effects_name(effects);
        aovs.attributes[attr::kBeautyEffects] = beauty_effects(effects, lens);
        aovs.attributes[attr::kBeauty] = std::string(beauty_holds::kMaaf6);  // what maaf6 replaces
        aovs.attributes[attr::kMaaf6SamplingS] = float(sampling_s);
        aovs.attributes[attr::kMaaf6PrefilterS] =
            float(std::chrono::duration<double>(Clock::now() - accumulate_start).count());
    }

  private:
    Maaf6GroupSettings settings_;
};

}  // namespace

std::unique_ptr<AovAccumulator> make_maaf6_group() {
    return std::make_unique<Maaf6Group>();
}

}  // namespace aaf::trace
