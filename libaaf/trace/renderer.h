#pragma once

#include <cstdint>
#include <limits>

#include "aaf/trace/render.h"
#include "embree_scene.h"
#include "light_sampler.h"
#include "scene_description.h"

namespace aaf::trace {

/// What the primary ray through a pixel's centre sees.
struct PrimaryHit {
    bool found = false;
    Vec3 position;  ///< world metres
    Vec3 normal;    ///< unit geometric normal, facing the camera
    const Mesh *mesh = nullptr;
    float pixel_size_m = 0;  ///< d of AAF Eq. 6
    Vec3 unshadowed;         ///< r(x) of AAF Eq. 1
};

/// Shadow-ray statistics of one pixel, accumulated over passes.
struct ShadowStats {
    std::uint32_t taken = 0;
    double weight_sum = 0;             ///< sum of the samples' light-function weights
    double unoccluded_weight_sum = 0;  ///< the same over unoccluded samples
    float d2_min_m = std::numeric_limits<float>::infinity();
    float d2_max_m = 0;

    void add_occluder(float d2_m) {
        d2_min_m = d2_m < d2_min_m ? d2_m : d2_min_m;
        d2_max_m = d2_m > d2_max_m ? d2_m : d2_max_m;
    }
    bool occluded_any() const { return d2_max_m > 0; }
    /// Light-weighted visibility in [0, 1]; exactly 1 when no sample was occluded.
    float visibility() const { return weight_sum > 0 ? float(unoccluded_weight_sum / weight_sum) : 1.0f; }
};

/// Traces primary and shadow rays of one scene (thread-safe, const).
class Renderer {
  public:
    Renderer(const SceneDescription &scene, const RenderSettings &settings);

    PrimaryHit trace_primary(int x, int y) const;

    /// Traces `count` shadow rays of pass `pass`, stratified among themselves,
    /// and adds them to `stats`.
    void trace_shadows(const PrimaryHit &primary, std::uint64_t pixel_index, std::uint32_t pass,
                       std::uint32_t count, ShadowStats &stats) const;

  private:
    float pixel_footprint(const PrimaryHit &primary, int x, int y) const;
    /// Geometric factor cos(receiver) cos(light) / r^2 from `p` (normal `n`) to a light point.
    float falloff(Vec3 p, Vec3 n, Vec3 light_point) const;
    /// Exact unshadowed irradiance factor with falloff: the profile-weighted
    /// mean of falloff() over the light, by a 16x16 midpoint quadrature in the sampler's warped coordinates.
    float mean_falloff(Vec3 p, Vec3 n) const;

    const SceneDescription &scene_;
    const RenderSettings &settings_;
    EmbreeScene bvh_;
    LightSampler light_sampler_;
};

}  // namespace aaf::trace
