#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "aaf/trace/render.h"
#include "light_sample.h"
#include "light_sampler.h"
#include "random.h"
#include "ray_queries.h"
#include "scene_description.h"

namespace aaf::trace {

class AovAccumulator;
class EmbreeScene;

/// What the central (pinhole) primary ray through a pixel's centre sees.
struct PrimaryHit {
    bool found = false;
    Vec3 position;  ///< world metres
    Vec3 normal;    ///< unit geometric normal, facing the camera
    const Mesh *mesh = nullptr;
    float pixel_size_m = 0;  ///< d of AAF Eq. 6
    float depth_m = 0;       ///< distance along the camera's forward axis
    Vec3 unshadowed;         ///< r(x) of AAF Eq. 1 for the key light
};

/// Shadow-ray statistics of one pixel, accumulated over passes.
struct ShadowStats {
    std::uint32_t taken = 0;
    double weight_sum = 0;             ///< sum of the key light samples' light-function weights
    double unoccluded_weight_sum = 0;  ///< the same over unoccluded samples
    float d2_min_m = std::numeric_limits<float>::infinity();
    float d2_max_m = 0;
    /// Sum over samples of the radiance that does not factor as r(x) V(x):
    /// the other lights' shadowed shading, and with a thin lens the whole
    /// beauty (seen through the lens sample's ray).
    double radiance_sum[3] = {0, 0, 0};

    void add_occluder(float d2_m) {
        d2_min_m = d2_m < d2_min_m ? d2_m : d2_min_m;
        d2_max_m = d2_m > d2_max_m ? d2_m : d2_max_m;
    }
    /// Adds one sample: the key light's weights and occluder distance, and
    /// the radiance traced apart from r(x) V(x).
    void add(const LightSample &sample) {
        ++taken;
        if (sample.has_receiver) {
            weight_sum += sample.weight;
            if (sample.visible)
                unoccluded_weight_sum += sample.weight;
            else if (sample.d2_m > 0)  // 0: self-occluded and skipped (RenderSettings::skip_self_occluded)
                add_occluder(sample.d2_m);
        }
        radiance_sum[0] += sample.radiance.x;
        radiance_sum[1] += sample.radiance.y;
        radiance_sum[2] += sample.radiance.z;
    }
    /// add() of `count` samples with a receiver, weight 1, no occluder
    /// distance and no radiance, visible[k] each: the same sums. Whole sums
    /// below 2^52 take the counts at once (adding 1 n times is exact there).
    void add_unit_weights(const bool *visible, std::uint32_t count) {
        std::uint32_t unoccluded = 0;
        for (std::uint32_t k = 0; k < count; ++k) unoccluded += visible[k] ? 1u : 0u;
        taken += count;
        auto whole = [](double sum) { return sum < 0x1p52 && sum == double(std::uint64_t(sum)); };
        if (whole(weight_sum) && whole(unoccluded_weight_sum)) {
            weight_sum += double(count);
            unoccluded_weight_sum += double(unoccluded);
            return;
        }
        for (std::uint32_t k = 0; k < count; ++k) {
            weight_sum += 1.0;
            if (visible[k]) unoccluded_weight_sum += 1.0;
        }
    }
    bool occluded_any() const { return d2_max_m > 0; }
    /// Light-weighted visibility in [0, 1]; exactly 1 when no sample was occluded.
    float visibility() const { return weight_sum > 0 ? float(unoccluded_weight_sum / weight_sum) : 1.0f; }
    /// Mean over the samples of the radiance traced apart from r(x) V(x).
    Vec3 mean_radiance() const {
        const double n = taken > 0 ? double(taken) : 1.0;
        return {float(radiance_sum[0] / n), float(radiance_sum[1] / n), float(radiance_sum[2] / n)};
    }
    /// Rounds the sums to float, the precision a checkpoint file stores them
    /// in, so a resumed render continues from exactly the same state.
    void round_to_float() {
        weight_sum = double(float(weight_sum));
        unoccluded_weight_sum = double(float(unoccluded_weight_sum));
        for (double &sum : radiance_sum) sum = double(float(sum));
    }
};

/// How a Renderer's own EmbreeScene sends visibility-only key-light shadow
/// rays to Embree: one at a time (rtcOccluded1), in packets of up to 16 of a pixel's rays (rtcOccluded16),
/// or Automatic: packets for renders of a round or more (a reference's
/// high-quality BVH, where they measured faster). Every choice gives the same
/// answers; only the speed differs.
enum class ShadowRayGrouping { Automatic, Single, Packets };

/// Traces primary and shadow rays of one scene and shades their hits
/// (thread-safe, const). Every ray goes through a RayQueries backend: its
/// own EmbreeScene, or one it is given.
class Renderer {
  public:
    /// Over an EmbreeScene of its own: a high-quality BVH for renders of a
    /// round or more, shadow rays grouped as `grouping` says.
    Renderer(const SceneDescription &scene, const RenderSettings &settings,
             ShadowRayGrouping grouping = ShadowRayGrouping::Automatic);
    /// Over `rays`, which must outlive it.
    Renderer(const SceneDescription &scene, const RenderSettings &settings, const RayQueries &rays);
    ~Renderer();
    Renderer(const Renderer &) = delete;
    Renderer &operator=(const Renderer &) = delete;

    PrimaryHit trace_primary(int x, int y) const;
    /// trace_primary() of pixels [x_begin, x_end) of row y into
    /// primaries[x - x_begin], their camera rays in one batch.
    void trace_primaries(int y, int x_begin, int x_end, PrimaryHit *primaries) const;

    /// Traces `count` samples of pass `pass`, stratified among themselves,
    /// and adds them to `stats` and to each of `listeners` (add_sample with
    /// `pixel_index`): one key-light shadow ray from the primary hit each,
    /// plus one per other light and, with a thin lens, a lens ray. With
    /// `occluder_distances` false the key light's rays ask for visibility
    /// only (any hit, cheaper than the closest) and every sample's d2_m is 0.
    void trace_shadows(const PrimaryHit &primary, int x, int y, std::uint64_t pixel_index, std::uint32_t pass,
                       std::uint32_t count, bool occluder_distances, ShadowStats &stats,
                       const std::vector<AovAccumulator *> &listeners) const;

    /// True when the beauty is not r(x) times the key light's visibility.
    bool has_separate_radiance() const { return scene_.lights.size() > 1 || scene_.camera.is_thin_lens(); }

    /// The backend every ray goes through.
    const RayQueries &rays() const { return rays_; }

    /// ISG's hard shadow (Sec. 3.1): one ray from the primary hit to the key
    /// light's centre. visible, or the distance from the hit to the first
    /// occluder (0 for a light behind the hit's own tangent plane).
    struct CentreShadow {
        bool visible = true;
        float occluder_m = 0;
    };
    CentreShadow trace_centre_shadow(const PrimaryHit &primary) const;
    /// What a ray from the primary hit along unit `direction` sees: the
    /// radiance of the surface it hits, every light shaded towards its centre
    /// with a hard shadow, and its distance (0 and no radiance on a miss).
    struct SecondaryHit {
        Vec3 radiance;
        float distance_m = 0;
    };
    SecondaryHit trace_secondary(const PrimaryHit &primary, Vec3 direction) const;
    /// Whether the shadow ray from the primary hit to `light_point` is
    /// blocked: by the scene, or by the surface itself when the point lies
    /// behind the hit's (geometric) tangent plane. The AAF samples' test.
    bool light_point_blocked(const PrimaryHit &primary, Vec3 light_point) const;

  private:
    Renderer(const SceneDescription &scene, const RenderSettings &settings,
             std::unique_ptr<EmbreeScene> owned);
    /// The primary hit of pixel (x, y) from its camera ray's closest hit.
    PrimaryHit primary_from(const Hit &hit, int x, int y) const;
    float pixel_footprint(const PrimaryHit &primary, int x, int y) const;
    /// Geometric factor cos(receiver) cos(light) / r^2 from `p` (normal `n`) to a light point.
    float falloff(const LightPlane &light, Vec3 p, Vec3 n, Vec3 light_point) const;
    /// Exact unshadowed irradiance factor with falloff: the profile-weighted
    /// mean of falloff() over the key light, by a 16x16 midpoint quadrature in
    /// the sampler's warped coordinates.
    float mean_falloff(Vec3 p, Vec3 n) const;
    /// r(x) of light `light_index` for a hit seen from `eye`: BRDF towards the
    /// light's centre times its irradiance there (AAF Eq. 1).
    Vec3 unshadowed(std::size_t light_index, const Mesh &mesh, Vec3 p, Vec3 n, Vec3 eye) const;
    /// Radiance at a surface point from lights [first_light, count), each
    /// r(x) times the visibility of one shadow ray towards the light's point
    /// for the unit-square sample `u`.
    Vec3 shade(const Mesh &mesh, Vec3 p, Vec3 n, Vec3 eye, UnitPoint u, std::size_t first_light) const;
    /// Fills `sample`'s weight, visibility and
    /// occluder distance for the key light seen from the primary hit, whose
    /// offset ray origin is `origin`, plane distance `d1` and falloff
    /// towards the light's centre `centre_falloff` (0 without the falloff);
    /// the occluder distance only with `occluder_distances` (else 0). The
    /// light point is `sample`'s (y_u_m, y_v_m), already warped;
    /// `traced_visibility`, when not null, is that visibility-only ray's
    /// answer, already traced (trace_visibility_batch).
    void trace_key_light(const PrimaryHit &primary, Vec3 origin, float d1, float centre_falloff,
                         bool occluder_distances, const bool *traced_visibility, LightSample &sample) const;
    /// Visibility-only shadow rays of `count` light points (y_u_m[k],
    /// y_v_m[k]) from the primary hit's offset `origin`, in one batched
    /// RayQueries::occluded() call: visible[k], false for a point behind the
    /// hit's tangent plane (no ray, as in trace_key_light).
    void trace_visibility_batch(const PrimaryHit &primary, Vec3 origin, std::uint32_t count,
                                const float *y_u_m, const float *y_v_m, bool *visible) const;
    /// The key light's closest-hit shadow rays of `count` light points
    /// (y_u_m[k], y_v_m[k]) from the primary hit's offset `origin` (plane
    /// distance `d1`), each as trace_key_light traces it with occluder
    /// distances: visible[k], and each occluded sample's d2 added to `stats`'
    /// d2min/d2max (the weight sums are the caller's).
    void trace_distance_batch(const PrimaryHit &primary, Vec3 origin, float d1, std::uint32_t count,
                              const float *y_u_m, const float *y_v_m, bool *visible,
                              ShadowStats &stats) const;
    /// The radiance `sample` traces apart from r(x) V(x): the other lights'
    /// shading at the primary hit, or with a thin lens that of every light
    /// seen through a lens ray aimed at `focus` (filling the sample's lens
    /// point from `lens_rng`).
    Vec3 separate_radiance(const PrimaryHit &primary, Vec3 focus, PixelRng &lens_rng,
                           LightSample &sample) const;
    /// Whether a shadow ray from surface point `p` (normal `n`, facing the
    /// ray's side) to `target` is blocked.
    bool occluded(Vec3 p, Vec3 n, Vec3 target) const;

    const SceneDescription &scene_;
    const RenderSettings &settings_;
    std::unique_ptr<EmbreeScene> owned_rays_;  ///< the backend, when the renderer built it
    const RayQueries &rays_;
    std::vector<LightSampler> light_samplers_;
};

}  // namespace aaf::trace
