#pragma once

#include <cstdint>
#include <vector>

#include "aaf/core/light_plane.h"

namespace aaf::trace {

/// Inverse CDF of a standard normal truncated to [-limit, limit], tabulated
/// once per light: 4096 intervals with linear interpolation, accurate to about
/// 1e-7 sigma for limit = 1 (the default light) and to 1e-3 sigma at limit 3.
class TruncatedNormal {
  public:
    explicit TruncatedNormal(double limit_sigmas);
    /// Maps u in [0, 1) to x in [-limit, limit] (units of sigma) with density
    /// proportional to exp(-x^2 / 2).
    float sample(float u) const;
    double limit() const { return limit_; }

  private:
    double limit_;
    std::vector<float> table_;
};

/// Draws points on a planar light proportionally to its emission profile, so
/// the light-weighted visibility is the plain fraction of unoccluded samples.
/// Samples are stratified: `count` samples fill a grid of ceil(sqrt(count))
/// columns and enough rows, one per stratum, in a per-pixel random order
/// (3x3 strata for 9 samples), each jittered within its stratum; the two
/// axes are sampled independently, which is exact for the separable truncated
/// Gaussian and for the uniform profile.
class LightSampler {
  public:
    explicit LightSampler(const LightPlane &light);

    /// Point of sample `index` of `count` for a pixel; `stratum_key` picks the
    /// pixel's order of strata, `u1, u2` in [0, 1) the jitter.
    Vec3 sample(std::uint32_t index, std::uint32_t count, std::uint32_t stratum_key, float u1,
                float u2) const;

    /// The stratified unit-square point of the same sample, before warping.
    static void stratified_unit(std::uint32_t index, std::uint32_t count, std::uint32_t stratum_key, float u1,
                                float u2, float &s, float &t);

    /// Offset along one axis, metres, for a unit-interval coordinate.
    float warp_u(float s) const;
    float warp_v(float t) const;

  private:
    LightPlane light_;
    TruncatedNormal normal_u_, normal_v_;
};

}  // namespace aaf::trace
