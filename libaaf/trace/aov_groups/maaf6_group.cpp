#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "../path_sample.h"
#include "aaf/core/methods/maaf/maaf_roles.h"
#include "aaf/core/methods/maaf6/maaf6_components.h"
#include "aaf/core/methods/maaf6/maaf6_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"
#include "aov_groups.h"

namespace aaf::trace {

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

/// MAAF for combined effects (Sec. 6.2) in two passes: 16 path samples give
/// each pixel's slopes (direct, indirect, defocus), averaged over 5x5; pixels
/// whose defocus slopes straddle 0 (the focal-plane box) get extra samples;
/// then every sample is accumulated into the 6D product channels, direct and
/// indirect apart. The group traces its own path samples when it writes
/// (through the render's Renderer, as isg does); the render's beauty is
/// replaced by the mean of direct + indirect.
class Maaf6Group final : public AovAccumulator {
  public:
    AovGroupInfo info() const override {
        AovGroupInfo info = group_info(
            "maaf6",
            "maaf6.direct.*, maaf6.indirect.* (75 sums + 25 weights each, N = 3), maaf6 wedges, maaf6.spp; "
            "traces its own path samples (lens, area light, one diffuse bounce) and replaces R, G, B",
            roles());
        info.parameters = {
            ParameterInfo::text("maaf6_effects", "defocus,shadows,indirect", "",
                                "the effects its path samples trace, any of defocus,shadows,indirect")};
        info.in_all = false;  // traces path samples of its own
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
        effects_ = parse_maaf6_effects(values.get_text("maaf6_effects"));
    }

    void write(const RenderState &state, AovSet &aovs) const override;

  private:
    unsigned effects_ = kMaaf6Defocus | kMaaf6Shadows | kMaaf6Indirect;
};

void Maaf6Group::write(const RenderState &state, AovSet &aovs) const {
    if (!state.renderer) throw Error("the maaf6 group needs the render's tracer");
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const int width = state.width, height = state.height;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    const SceneDescription &scene = state.scene;
    const Camera &camera = scene.camera;
    const LightPlane &light = scene.key_light();
    const unsigned effects = effects_;
    const PathSampler sampler(scene, state.renderer->rays(), effects);
    const bool lens = (effects & kMaaf6Defocus) && camera.is_thin_lens();
    const int first_spp = std::min(kFirstPassSpp, state.spp);

    // Each pixel's tangent frame (maaf6_tangent_frame), from the central primary hit's normal.
    std::vector<Vec3> t1(count), t2(count);
    for (std::size_t i = 0; i < count; ++i)
        if (state.primaries[i].found)
            maaf6_tangent_frame(state.primaries[i].normal, light.axis_u, light.axis_v, t1[i], t2[i]);

    std::vector<std::vector<Stored>> samples(count);
    std::vector<RawWedge> raw(count);
    auto trace = [&](std::size_t i, int x, int y, std::uint32_t pass, int n) {
        PixelRng rng(state.seed ^ kMaaf6Stream, i, pass);
        const StratifiedGrid strata(std::uint32_t(std::max(1, n)));
        const std::uint32_t keys[4] = {rng.next_u32(), rng.next_u32(), rng.next_u32(), rng.next_u32()};
        for (int k = 0; k < n; ++k) {
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
            const PathSample s = sampler.trace(x, y, numbers);
            Stored stored{};
            stored.y1_direct = dot(s.light_offset_m, t1[i]);
            stored.y2_direct = dot(s.light_offset_m, t2[i]);
            stored.u1 = dot(s.lens_offset_m, t1[i]);
            stored.u2 = dot(s.lens_offset_m, t2[i]);
            const Vec3 n = state.primaries[i].normal;
            const float cos_n = dot(s.bounce_direction, n);
            if (cos_n > 1e-3f) {  // the unit plane above the receiver (AAF-GI's parametrisation)
                stored.y1_indirect = dot(s.bounce_direction, t1[i]) / cos_n;
                stored.y2_indirect = dot(s.bounce_direction, t2[i]) / cos_n;
            }
            stored.direct_unoccluded_y = 0.2126f * s.direct_unoccluded.x + 0.7152f * s.direct_unoccluded.y +
                                         0.0722f * s.direct_unoccluded.z;
            for (int c = 0; c < 3; ++c) {
                stored.direct[c] = s.direct[c];
                stored.indirect[c] = s.indirect[c];
            }
            samples[i].push_back(stored);
            if (pass != 0 || !s.hit) continue;
            RawWedge &w = raw[i];
            if (s.direct_slope >= 0) {
                w.direct_min = std::min(w.direct_min, s.direct_slope);
                w.direct_max = std::max(w.direct_max, s.direct_slope);
            }
            if (s.bounce_height_m > 0) {
                w.indirect_min = std::min(w.indirect_min, s.bounce_height_m);
                w.indirect_max = std::max(w.indirect_max, s.bounce_height_m);
            }
            const float u_slope =
                1.0f - s.depth_m / camera.focus_distance_m;  // s_u = 1 - z/F (methods/maaf6/README.md)
            w.u_min = std::min(w.u_min, u_slope);
            w.u_max = std::max(w.u_max, u_slope);
        }
    };
    // MAAF Sec. 6.2 "Sampling": the first pass.
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x)
            trace(std::size_t(y) * std::size_t(width) + std::size_t(x), x, y, 0, first_spp);
    });

    // MAAF Sec. 6.2 "Pre-filtering": slopes averaged over 5x5 (pixels with a
    // central hit, normals within 20 degrees; defocus slopes over every pixel with a hit).
    std::vector<float> direct_min(count, -1), direct_max(count, -1), indirect_min(count, -1),
        indirect_max(count, -1), u_min(count, 0), u_max(count, 0), omega_x(count, 0);
    const float cos_threshold = std::cos(kNormalThresholdDeg * 3.14159265f / 180.0f);
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            const PrimaryHit &centre = state.primaries[i];
            if (!centre.found) continue;
            double sums[6] = {0, 0, 0, 0, 0, 0};
            int used_direct = 0, used_indirect = 0, used_u = 0;
            for (int ty = std::max(0, y - kPrefilterRadiusPx);
                 ty <= std::min(height - 1, y + kPrefilterRadiusPx); ++ty)
                for (int tx = std::max(0, x - kPrefilterRadiusPx);
                     tx <= std::min(width - 1, x + kPrefilterRadiusPx); ++tx) {
                    const std::size_t t = std::size_t(ty) * std::size_t(width) + std::size_t(tx);
                    const RawWedge &w = raw[t];
                    if (w.u_min <= w.u_max) {
                        sums[4] += w.u_min;
                        sums[5] += w.u_max;
                        ++used_u;
                    }
                    if (!state.primaries[t].found ||
                        dot(state.primaries[t].normal, centre.normal) < cos_threshold)
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
            if (used_direct > 0) {
                direct_min[i] = float(sums[0] / used_direct);
                direct_max[i] = std::max(direct_min[i], float(sums[1] / used_direct));
            }
            if (used_indirect > 0) {
                indirect_min[i] = float(sums[2] / used_indirect);
                indirect_max[i] = std::max(indirect_min[i], float(sums[3] / used_indirect));
            }
            if (used_u > 0) {
                u_min[i] = float(sums[4] / used_u);
                u_max[i] = std::max(u_min[i], float(sums[5] / used_u));
            }
            omega_x[i] = float(kPixelBand / std::max(1e-9f, centre.pixel_size_m));
        }
    });

    // The rest of the samples, and the focal-plane pixels' extra ones.
    const double omega_u = lens ? 4.0 / double(camera.aperture_radius_m) : 0.0;  // MAAF Sec. 3, L = A
    const double omega_direct = 2.0 / double(light.sigma_m);                     // MAAF Sec. 3: 2 / sigma_y
    std::vector<int> extra(count, 0);
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            if (state.spp > first_spp) trace(i, x, y, 1, state.spp - first_spp);
            if (lens && state.primaries[i].found && u_min[i] * u_max[i] < 0) {
                // Stand-in for MYRD14 Sec. 7's rate (not among the shared papers): the box
                // spans the whole lens band, so the samples scale with the lens band's
                // periods across the aperture, (1 + A Omega_u^max / (2 pi))^2, capped at +100.
                const double scale =
                    1.0 + double(camera.aperture_radius_m) * omega_u / (2.0 * 3.14159265358979);
                extra[i] = std::min(kMaxExtraSpp, int(std::ceil(state.spp * scale * scale)) - state.spp);
                trace(i, x, y, 2, extra[i]);
            }
        }
    });
    const double sampling_s = std::chrono::duration<double>(Clock::now() - start).count();
    const auto accumulate_start = Clock::now();

    const std::vector<PlaneView> direct_views = add_role_channels(aovs, roles::Maaf6Direct);
    const std::vector<PlaneView> indirect_views = add_role_channels(aovs, roles::Maaf6Indirect);
    const std::vector<PlaneView> direct_sums = add_role_channels(aovs, roles::Maaf6DirectSums);
    const std::vector<PlaneView> direct_weights = add_role_channels(aovs, roles::Maaf6DirectWeights);
    const std::vector<PlaneView> indirect_sums = add_role_channels(aovs, roles::Maaf6IndirectSums);
    const std::vector<PlaneView> indirect_weights = add_role_channels(aovs, roles::Maaf6IndirectWeights);
    const std::vector<PlaneView> wedge_views = add_role_channels(aovs, roles::Maaf6Wedge);
    const std::vector<PlaneView> spp_view = add_role_channels(aovs, roles::Maaf6Spp);
    const PlaneView beauty[3] = {aovs.channel("R"), aovs.channel("G"), aovs.channel("B")};
    aovs.attributes[attr::kBeauty] = std::string(beauty_holds::kMaaf6);  // what maaf6 replaces
    const int channels = maaf6_channel_count(kMaafContractPairs);
    // MAAF Eq. 23: each layer's sums with its pixel's parameters.
    parallel_for_rows(height, [&](int y) {
        std::vector<double> rgb(static_cast<std::size_t>(3 * channels)),
            weight(static_cast<std::size_t>(channels));
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            const std::vector<Stored> &mine = samples[i];
            const double n = mine.empty() ? 1.0 : double(mine.size());
            double mean_direct[3] = {0, 0, 0}, mean_indirect[3] = {0, 0, 0};
            for (const Stored &s : mine)
                for (int c = 0; c < 3; ++c) {
                    mean_direct[c] += s.direct[c] / n;
                    mean_indirect[c] += s.indirect[c] / n;
                }
            for (int c = 0; c < 3; ++c) {
                direct_views[std::size_t(c)](x, y) = float(mean_direct[c]);
                indirect_views[std::size_t(c)](x, y) = float(mean_indirect[c]);
                beauty[c](x, y) = float(mean_direct[c] + mean_indirect[c]);
            }
            wedge_views[0](x, y) = direct_min[i];
            wedge_views[1](x, y) = direct_max[i];
            wedge_views[2](x, y) = indirect_min[i];
            wedge_views[3](x, y) = indirect_max[i];
            wedge_views[4](x, y) = u_min[i];
            wedge_views[5](x, y) = u_max[i];
            wedge_views[6](x, y) = omega_x[i];
            spp_view[0](x, y) = float(mine.size());
            for (int layer = 0; layer < 2; ++layer) {
                std::fill(rgb.begin(), rgb.end(), 0.0);
                std::fill(weight.begin(), weight.end(), 0.0);
                const bool is_direct = layer == 0;
                std::vector<Maaf6Component> pairs(1);
                if (state.primaries[i].found) {
                    Maaf6Wedge wedge;
                    const float lo = is_direct ? direct_min[i] : indirect_min[i];
                    const float hi = is_direct ? direct_max[i] : indirect_max[i];
                    wedge.has_y = lo >= 0 && hi >= 0;
                    wedge.y_min = wedge.has_y ? double(lo) : 0.0;
                    wedge.y_max = wedge.has_y ? double(hi) : 0.0;
                    wedge.omega_y_max = is_direct ? omega_direct : kIndirectOmegaMax;
                    wedge.has_u = lens;
                    wedge.u_min = double(u_min[i]);
                    wedge.u_max = double(u_max[i]);
                    wedge.omega_u_max = omega_u;
                    wedge.omega_x_max = double(omega_x[i]);
                    pairs = maaf6_pair_components(wedge, kMaafContractPairs);
                } else {
                    pairs.resize(
                        std::size_t(kMaafContractPairs));  // background: phases 0, only the mean matters
                }
                const Maaf6SampleSide side(pairs);
                for (const Stored &s : mine)
                    side.accumulate(
                        is_direct ? s.y1_direct : s.y1_indirect, s.u1,
                        is_direct ? s.y2_direct : s.y2_indirect, s.u2, is_direct ? s.direct : s.indirect,
                        is_direct ? double(s.direct_unoccluded_y) : 1.0, rgb.data(), weight.data());
                const std::vector<PlaneView> &sums = is_direct ? direct_sums : indirect_sums;
                const std::vector<PlaneView> &weights = is_direct ? direct_weights : indirect_weights;
                for (int c = 0; c < channels; ++c) {
                    weights[std::size_t(c)](x, y) = float(weight[std::size_t(c)]);
                    for (int k = 0; k < 3; ++k)
                        sums[std::size_t(3 * c + k)](x, y) = float(rgb[std::size_t(3 * c + k)]);
                }
            }
        }
    });
    aovs.attributes[attr::kMaaf6Pairs] = kMaafContractPairs;
    aovs.attributes[attr::kMaaf6OmegaDirect] = float(omega_direct);
    aovs.attributes[attr::kMaaf6OmegaIndirect] = float(kIndirectOmegaMax);
    aovs.attributes[attr::kMaaf6OmegaLens] = float(omega_u);
    aovs.attributes[attr::kMaaf6Effects] = maaf6_effects_name(effects);
    aovs.attributes[attr::kMaaf6SamplingS] = float(sampling_s);
    aovs.attributes[attr::kMaaf6PrefilterS] =
        float(std::chrono::duration<double>(Clock::now() - accumulate_start).count());
}

}  // namespace

std::unique_ptr<AovAccumulator> make_maaf6_group() {
    return std::make_unique<Maaf6Group>();
}

}  // namespace aaf::trace
