#include "truncated_normal.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "aaf/core/util/error.h"
#include "truncated_normal_batch.h"

namespace aaf::trace {

namespace {

/// Largest error of an interval's cubic, sigma, before it falls back to the
/// exact inverse; float rounding of the result adds at most half an ulp.
constexpr double kCubicTolerance = 1e-7;
constexpr double kInvSqrt2 = 0.70710678118654752440;
constexpr double kInvSqrt2Pi = 0.39894228040143267794;

double standard_normal_cdf(double x) {
    return 0.5 * std::erfc(-x * kInvSqrt2);
}
double standard_normal_pdf(double x) {
    return kInvSqrt2Pi * std::exp(-0.5 * x * x);
}

}  // namespace

TruncatedNormal::TruncatedNormal(double limit_sigmas) : limit_(limit_sigmas) {
    // Beyond 8 sigma the density at the edge underflows the slopes' float range.
    if (!(limit_sigmas > 0) || limit_sigmas > 8)
        throw Error("Gaussian light truncation must lie in (0, 8] sigma, got " +
                    std::to_string(limit_sigmas));
    cdf_low_ = standard_normal_cdf(-limit_);
    mass_ = standard_normal_cdf(limit_) - cdf_low_;

    // Nodes x_i = cdf^-1(i / N) and slopes dx/dt = (1 / N) mass / phi(x_i),
    // t being the position inside an interval.
    constexpr double kStep = 1.0 / kIntervals;
    std::vector<double> node(kIntervals + 1), slope(kIntervals + 1);
    node.front() = -limit_;
    node.back() = limit_;
    for (int i = 0; i <= kIntervals; ++i) {
        if (i > 0 && i < kIntervals) {
            const double guess = std::min(node[i - 1] + slope[i - 1], limit_);
            node[i] = solve(double(i) * kStep, node[i - 1], limit_, guess);
        }
        slope[i] = kStep * mass_ / standard_normal_pdf(node[i]);
    }

    cubics_.resize(kIntervals + 1);
    exact_.assign(kIntervals, 0);
    for (int i = 0; i < kIntervals; ++i) {
        // Cubic Hermite through (0, x_i) and (1, x_i+1) with the slopes at both ends.
        const double rise = node[i + 1] - node[i];
        const double c2 = 3 * rise - 2 * slope[i] - slope[i + 1];
        const double c3 = -2 * rise + slope[i] + slope[i + 1];
        cubics_[i] = {float(node[i]), float(slope[i]), float(c2), float(c3)};
        for (double t : {0.25, 0.5, 0.75}) {
            const double cubic = node[i] + t * (slope[i] + t * (c2 + t * c3));
            const double exact = solve((double(i) + t) * kStep, node[i], node[i + 1], cubic);
            if (!(std::fabs(cubic - exact) <= kCubicTolerance)) exact_[i] = 1;
        }
    }
    cubics_.back() = {float(limit_), 0, 0, 0};
    any_exact_ = std::find(exact_.begin(), exact_.end(), 1) != exact_.end();
}

void TruncatedNormal::sample_scaled(const float *u, std::size_t count, float scale, float *out) const {
    if (any_exact_) {
        for (std::size_t k = 0; k < count; ++k) out[k] = scale * sample(u[k]);
        return;
    }
    detail::sample_cubic_batch(&cubics_.front().x0, kIntervals, float(limit_), u, count, scale, out);
}

double TruncatedNormal::cdf(double x) const {
    if (x <= -limit_) return 0;
    if (x >= limit_) return 1;
    return std::clamp((standard_normal_cdf(x) - cdf_low_) / mass_, 0.0, 1.0);
}

double TruncatedNormal::solve(double u, double low, double high, double guess) const {
    if (!(u > 0)) return -limit_;
    if (u >= 1) return limit_;
    double x = std::clamp(guess, low, high);
    for (int iteration = 0; iteration < 200; ++iteration) {
        const double residual = cdf(x) - u;
        if (residual == 0) return x;
        (residual < 0 ? low : high) = x;
        // Newton on the CDF, falling back to bisection when it leaves the bracket.
        double next = x - residual * mass_ / standard_normal_pdf(x);
        if (!(next > low && next < high)) next = 0.5 * (low + high);
        if (std::fabs(next - x) <= 1e-15 * (1 + std::fabs(x))) return next;
        x = next;
    }
    return x;
}

double TruncatedNormal::inverse_cdf(double u) const {
    return solve(u, -limit_, limit_, 0.0);
}

float TruncatedNormal::exact_sample(float u, float x0, float x1) const {
    return float(solve(double(u), -limit_, limit_, 0.5 * (double(x0) + double(x1))));
}

}  // namespace aaf::trace
