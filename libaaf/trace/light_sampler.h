#pragma once

#include <cstddef>

#include "aaf/core/contract/light_plane.h"
#include "stratified_grid.h"
#include "truncated_normal.h"

namespace aaf::trace {

/// Maps unit-square points onto a planar light, with density proportional to
/// its emission profile l(y), so the light-weighted visibility of AAF Eq. 1
/// is the plain fraction of unoccluded samples. The two tangent axes are
/// warped independently, which is exact for the separable Gaussian truncated
/// to the rectangle (inverse CDF of a truncated normal per axis) and for the
/// uniform profile (a linear map).
class LightSampler {
  public:
    /// Throws aaf::Error when the light is invalid or its Gaussian is
    /// truncated beyond 8 sigma.
    explicit LightSampler(const LightPlane &light);

    /// World point of the light for `p` in [0, 1)^2.
    Vec3 point(UnitPoint p) const { return light_.point_at(warp_u(p.s), warp_v(p.t)); }

    /// Offset from the centre along axis_u, metres, for s in [0, 1].
    float warp_u(float s) const {
        return gaussian_ ? light_.sigma_m * normal_u_.sample(s) : (s - 0.5f) * light_.width_m;
    }
    /// Offset from the centre along axis_v, metres, for t in [0, 1].
    float warp_v(float t) const {
        return gaussian_ ? light_.sigma_m * (square_ ? normal_u_ : normal_v_).sample(t)
                         : (t - 0.5f) * light_.height_m;
    }

    /// u_m[k] = warp_u(s[k]) and v_m[k] = warp_v(t[k]) for k < count: the
    /// same operations and bits, one tight loop per axis (a pixel's batch).
    void warp(const float *s, const float *t, std::size_t count, float *u_m, float *v_m) const {
        if (!gaussian_) {
            for (std::size_t k = 0; k < count; ++k) u_m[k] = (s[k] - 0.5f) * light_.width_m;
            for (std::size_t k = 0; k < count; ++k) v_m[k] = (t[k] - 0.5f) * light_.height_m;
            return;
        }
        normal_u_.sample_scaled(s, count, light_.sigma_m, u_m);
        (square_ ? normal_u_ : normal_v_).sample_scaled(t, count, light_.sigma_m, v_m);
    }

  private:
    LightPlane light_;
    bool gaussian_;
    bool square_;  ///< both axes cut at the same sigma: one table serves both (half the cache)
    TruncatedNormal normal_u_, normal_v_;  ///< truncated at the rectangle's edges
};

}  // namespace aaf::trace
