#include "light_sampler.h"

#include <algorithm>
#include <cmath>

#include "aaf/core/error.h"
#include "random.h"

namespace aaf::trace {

namespace {

constexpr int kTableIntervals = 4096;

double standard_normal_cdf(double x) {
    return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

}  // namespace

TruncatedNormal::TruncatedNormal(double limit_sigmas) : limit_(limit_sigmas) {
    if (!(limit_sigmas > 0) || limit_sigmas > 8) throw Error("light truncation must lie in (0, 8] sigma");
    const double cdf_low = standard_normal_cdf(-limit_), mass = standard_normal_cdf(limit_) - cdf_low;
    table_.resize(kTableIntervals + 1);
    table_.front() = float(-limit_);
    table_.back() = float(limit_);
    for (int i = 1; i < kTableIntervals; ++i) {
        // Bisection on the truncated CDF: monotone, never fails, exact to double precision.
        const double target = double(i) / kTableIntervals;
        double low = -limit_, high = limit_;
        for (int iteration = 0; iteration < 64; ++iteration) {
            const double mid = 0.5 * (low + high);
            ((standard_normal_cdf(mid) - cdf_low) / mass < target ? low : high) = mid;
        }
        table_[i] = float(0.5 * (low + high));
    }
}

float TruncatedNormal::sample(float u) const {
    const float position = std::clamp(u, 0.0f, 1.0f) * kTableIntervals;
    const int i = std::min(int(position), kTableIntervals - 1);
    const float fraction = position - float(i);
    return table_[i] + fraction * (table_[i + 1] - table_[i]);
}

LightSampler::LightSampler(const LightPlane &light)
    : light_(light),
      normal_u_(0.5 * light.width_m / light.sigma_m),
      normal_v_(0.5 * light.height_m / light.sigma_m) {}

void LightSampler::stratified_unit(std::uint32_t index, std::uint32_t count, std::uint32_t stratum_key,
                                   float u1, float u2, float &s, float &t) {
    const std::uint32_t columns = std::uint32_t(std::ceil(std::sqrt(double(count))));
    const std::uint32_t rows = (count + columns - 1) / columns;
    const std::uint32_t stratum = permute_index(index, columns * rows, stratum_key);
    s = (float(stratum % columns) + u1) / float(columns);
    t = (float(stratum / columns) + u2) / float(rows);
    // Guard the float rounding of (k + u) / n at the top edge.
    s = std::min(s, 0x1.fffffep-1f);
    t = std::min(t, 0x1.fffffep-1f);
}

float LightSampler::warp_u(float s) const {
    return light_.profile == LightProfile::Gaussian ? light_.sigma_m * normal_u_.sample(s)
                                                    : (s - 0.5f) * light_.width_m;
}

float LightSampler::warp_v(float t) const {
    return light_.profile == LightProfile::Gaussian ? light_.sigma_m * normal_v_.sample(t)
                                                    : (t - 0.5f) * light_.height_m;
}

Vec3 LightSampler::sample(std::uint32_t index, std::uint32_t count, std::uint32_t stratum_key, float u1,
                          float u2) const {
    float s, t;
    stratified_unit(index, count, stratum_key, u1, u2, s, t);
    return light_.point_at(warp_u(s), warp_v(t));
}

}  // namespace aaf::trace
