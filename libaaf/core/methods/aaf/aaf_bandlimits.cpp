#include "aaf/core/methods/aaf/aaf_bandlimits.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aaf/core/methods/aaf/aaf_params.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"

namespace aaf {

const char *to_string(AafLightAxes axes) {
    return axes == AafLightAxes::Shortest ? "shortest" : "per_axis";
}

AafLightAxes light_axes_from_string(const std::string &name) {
    if (name == "per_axis") return AafLightAxes::PerAxis;
    if (name == "shortest") return AafLightAxes::Shortest;
    throw Error("unknown light axes rule " + quoted(name) + " (expected per_axis or shortest)");
}

float projected_pixel_size_m(float pixel_size_m, Vec3 receiver_normal, Vec3 light_normal) {
    const float length_n = length(receiver_normal);
    if (!(length_n > 0) || !std::isfinite(length_n)) return pixel_size_m;
    const float cos_planes = std::fabs(dot(receiver_normal, light_normal)) / length_n;
    return pixel_size_m * std::clamp(cos_planes, kDegenerateProjectionCos, 1.0f);
}

void AafParams::validate() const {
    if (!(mu > 0)) throw Error("AAF parameter mu must be positive");
    if (!(k > 0)) throw Error("AAF parameter k must be positive");
    if (!(alpha > 0 && alpha <= 1)) throw Error("AAF parameter alpha must lie in (0, 1]");
    if (!(normal_threshold_deg >= 0 && normal_threshold_deg <= 180))
        throw Error("AAF normal threshold must lie in [0, 180] degrees");
    if (fill_radius_px < 0) throw Error("AAF fill radius must be >= 0 pixels");
    if (max_radius_px < 0) throw Error("AAF maximum filter radius must be >= 0 pixels");
    if (!(fixed_beta_m >= 0)) throw Error("AAF fixed beta must be >= 0 metres");
    if (mu_from_spp && fixed_mu) throw Error("AAF mu from spp and fixed mu exclude each other");
}

namespace {

/// The part of aaf_bandlimits() that does not depend on mu: AAF Eq. 4, 6, 7, 8
/// (omega_x_f, beta_m and samples_per_pixel left 0).
AafBandlimits mu_free_bandlimits(float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m,
                                 float sigma_m, const AafParams &params) {
    AafBandlimits b;
    b.s1 = std::max(0.0f, d1_m / d2_min_m - 1.0f);               // AAF Eq. 4
    b.s2 = std::max(0.0f, d1_m / d2_max_m - 1.0f);               // AAF Eq. 4
    b.omega_light = 1.0f / sigma_m;                              // Sec. 4.1: Omega_L^max = 1/sigma
    const float omega_pixel = 1.0f / pixel_size_m;               // Sec. 4.1: Omega_pix^max = 1/d
    b.omega_x_max = params.alpha / (1.0f + b.s2) * omega_pixel;  // AAF Eq. 6
    b.omega_y_max = params.alpha * std::max(0.0f, 1.0f - d2_min_m / d1_m) * omega_pixel;  // AAF Eq. 7

    // AAF Eq. 8: Omega_L / s2 is unbounded as s2 -> 0; the clip to Omega_x^max takes over.
    const float light_induced = b.s2 > 0 ? b.omega_light / b.s2 : std::numeric_limits<float>::infinity();
    b.omega_x_f0 = std::min(light_induced, b.omega_x_max);
    return b;
}

/// AAF Eq. 15 at `mu` from mu_free_bandlimits(): a few multiplies, no divide,
/// so mu_for_samples' bisection can call it at every step. aaf_bandlimits()
/// takes its rate from here too, so both give the same bits.
float samples_per_pixel_at(const AafBandlimits &mu_free, float mu, float pixel_size_m, float sigma_m) {
    const float omega_x_f = mu * mu_free.omega_x_f0;  // Sec. 5.2
    // AAF Eq. 15 with packing (a) of Fig. 4: A_p = d^2 and A_l = (2 sigma)^2.
    const float omega_x_star = omega_x_f + mu_free.omega_x_max;
    const float omega_y_star = mu_free.omega_light + std::min(mu_free.s1 * omega_x_f, mu_free.omega_y_max);
    const float pixel_term = omega_x_star * pixel_size_m;
    const float light_term = omega_y_star * 2.0f * sigma_m;
    return pixel_term * pixel_term * light_term * light_term;
}

}  // namespace

AafBandlimits aaf_bandlimits(float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m, float sigma_m,
                             const AafParams &params) {
    AafBandlimits b = mu_free_bandlimits(d1_m, d2_min_m, d2_max_m, pixel_size_m, sigma_m, params);
    b.omega_x_f = params.mu * b.omega_x_f0;  // Sec. 5.2
    // AAF Eq. 13: beta = 1/(k mu) max(sigma s2, 1/Omega_x^max) = 1 / (k Omega_x^f).
    b.beta_m = 1.0f / (params.k * b.omega_x_f);
    b.samples_per_pixel = samples_per_pixel_at(b, params.mu, pixel_size_m, sigma_m);
    return b;
}

AafAxisBandlimits aaf_bandlimits_axes(float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m,
                                      LightBandlimitAxes sigma, const AafParams &params) {
    AafAxisBandlimits b;
    b.u = aaf_bandlimits(d1_m, d2_min_m, d2_max_m, pixel_size_m, sigma.u_m, params);
    if (sigma.v_m == sigma.u_m) {
        b.v = b.u;
        b.samples_per_pixel = b.u.samples_per_pixel;
        return b;
    }
    b.v = aaf_bandlimits(d1_m, d2_min_m, d2_max_m, pixel_size_m, sigma.v_m, params);
    // AAF Eq. 15 per axis: each aaf_bandlimits() rate is its axis's factor squared.
    b.samples_per_pixel = std::sqrt(b.u.samples_per_pixel) * std::sqrt(b.v.samples_per_pixel);
    return b;
}

LightBandlimitAxes aaf_light_sigmas_m(const LightPlane &light, const AafParams &params) {
    LightBandlimitAxes sigma = light_bandlimit_axes_m(light, params.light_bandlimit);
    if (params.light_axes == AafLightAxes::Shortest) sigma.u_m = sigma.v_m = std::min(sigma.u_m, sigma.v_m);
    return sigma;
}

float mu_for_samples(float samples, float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m,
                     float sigma_m, const AafParams &params) {
    return mu_for_samples(samples, d1_m, d2_min_m, d2_max_m, pixel_size_m,
                          LightBandlimitAxes{sigma_m, sigma_m}, params);
}

float mu_for_samples(float samples, float d1_m, float d2_min_m, float d2_max_m, float pixel_size_m,
                     LightBandlimitAxes sigma, const AafParams &params) {
    constexpr float kMaxMu = 1e4f;
    // The rate of aaf_bandlimits_axes() at mu, bit for bit, with the mu-free
    // terms (all of the divides) computed once instead of at every step.
    const bool square = sigma.v_m == sigma.u_m;
    const AafBandlimits u = mu_free_bandlimits(d1_m, d2_min_m, d2_max_m, pixel_size_m, sigma.u_m, params);
    const AafBandlimits v =
        square ? u : mu_free_bandlimits(d1_m, d2_min_m, d2_max_m, pixel_size_m, sigma.v_m, params);
    auto rate = [&](float mu) {
        const float rate_u = samples_per_pixel_at(u, mu, pixel_size_m, sigma.u_m);
        if (square) return rate_u;
        // AAF Eq. 15 per axis, as in aaf_bandlimits_axes().
        return std::sqrt(rate_u) * std::sqrt(samples_per_pixel_at(v, mu, pixel_size_m, sigma.v_m));
    };
    if (!(rate(params.mu) < samples)) return params.mu;
    if (rate(kMaxMu) <= samples) return kMaxMu;
    float low = params.mu, high = kMaxMu;
    while (high - low > 1e-4f * low) {
        const float mid = std::sqrt(low * high);  // geometric: mu spans decades
        (rate(mid) < samples ? low : high) = mid;
    }
    return low;
}

}  // namespace aaf
