#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace aaf::trace {

/// A standard normal truncated to [-limit, limit] (units of sigma): the
/// marginal of a Gaussian light profile along one of the light's axes.
///
/// `sample` inverts the CDF with a table of 4096 intervals in u, each a cubic
/// Hermite interpolant with the exact slopes dx/du = mass / phi(x). Where a
/// cubic is not accurate to 1e-7 sigma (checked at build time; in practice
/// only the extreme tails of wide truncations), that interval falls back to
/// the exact inverse. The result is within 1e-6 sigma of the exact inverse.
class TruncatedNormal {
  public:
    /// Throws aaf::Error unless 0 < limit_sigmas <= 8.
    explicit TruncatedNormal(double limit_sigmas);

    double limit() const { return limit_; }

    /// Cumulative distribution at x (units of sigma), in [0, 1].
    double cdf(double x) const;
    /// Exact inverse of cdf() by safeguarded Newton iteration on std::erfc,
    /// in double precision; u is clamped to [0, 1]. Slow: the reference.
    double inverse_cdf(double u) const;

    /// Fast inverse of cdf(): maps u in [0, 1] to x in [-limit, limit] with
    /// density proportional to exp(-x^2 / 2); monotone, never NaN (a NaN u
    /// maps to -limit).
    float sample(float u) const {             // inline: it runs twice per shadow ray
        if (!(u > 0)) return float(-limit_);  // also catches NaN
        if (u >= 1) return float(limit_);
        const float position = u * float(kIntervals);
        const int i = std::min(int(position), kIntervals - 1);
        const float t = position - float(i);
        const Cubic &c = cubics_[std::size_t(i)];
        const float next_x0 = cubics_[std::size_t(i) + 1].x0;
        if (exact_[std::size_t(i)]) return exact_sample(u, c.x0, next_x0);
        const float x = c.x0 + t * (c.slope0 + t * (c.c2 + t * c.c3));
        return std::clamp(x, c.x0, next_x0);  // keeps the map monotone across intervals
    }

    /// out[k] = scale * sample(u[k]) for k < count: the same bits as
    /// sample(), vectorised (truncated_normal_batch.h) unless some interval
    /// uses the exact inverse.
    void sample_scaled(const float *u, std::size_t count, float scale, float *out) const;

    static constexpr int kIntervals = 4096;  ///< of the inverse-CDF table in u

  private:
    /// The exact inverse for an interval whose cubic is not accurate enough.
    float exact_sample(float u, float x0, float x1) const;
    /// Root of cdf(x) = u inside [low, high], which must bracket it,
    /// starting from `guess`.
    double solve(double u, double low, double high, double guess) const;

    /// x(t) = x0 + t (slope0 + t (c2 + t c3)) for t in [0, 1] across one interval.
    struct Cubic {
        float x0, slope0, c2, c3;
    };
    static_assert(sizeof(Cubic) == 4 * sizeof(float), "the batch reads the table as floats");

    double limit_;
    double cdf_low_;                    ///< standard normal CDF at -limit
    double mass_;                       ///< standard normal probability of [-limit, limit]
    std::vector<Cubic> cubics_;         ///< one per interval, plus a sentinel holding x0 = limit
    std::vector<unsigned char> exact_;  ///< 1 where an interval uses the exact inverse
    bool any_exact_ = false;            ///< whether any interval does
};

}  // namespace aaf::trace
