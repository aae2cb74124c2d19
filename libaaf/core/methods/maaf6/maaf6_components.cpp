#include <algorithm>
#include <cmath>
#include <string>

#include "aaf/core/methods/maaf/maaf_accumulation.h"
#include "aaf/core/methods/maaf/maaf_components.h"
#include "aaf/core/methods/maaf6/maaf6_components.h"
#include "aaf/core/util/error.h"

namespace aaf {

namespace {

void check_wedge(const Maaf6Wedge &w, int pairs) {
    if (pairs < 1 || pairs > kMaafMaxPairs)
        throw Error("MAAF 6D: between 1 and " + std::to_string(kMaafMaxPairs) + " pairs, got " +
                    std::to_string(pairs));
    if (!(w.omega_x_max > 0) || !std::isfinite(w.omega_x_max))
        throw Error("MAAF 6D: the pixel band-limit must be positive and finite");
    if (w.has_y && (!(w.y_min >= 0) || !(w.y_max >= w.y_min) || !std::isfinite(w.y_max) ||
                    !(w.omega_y_max > 0) || !std::isfinite(w.omega_y_max)))
        throw Error("MAAF 6D: the y-wedge needs 0 <= y_min <= y_max < inf and a positive finite band");
    if (w.has_u && (!std::isfinite(w.u_min) || !std::isfinite(w.u_max) || w.u_max < w.u_min ||
                    !(w.omega_u_max > 0) || !std::isfinite(w.omega_u_max)))
        throw Error("MAAF 6D: the u-wedge needs finite u_min <= u_max and a positive finite band");
}

/// Both u slopes on one side of 0 (not the focal-plane box of MAAF Sec. 6.2).
bool one_signed(const Maaf6Wedge &w) {
    return w.has_u && w.u_min * w.u_max > 0;
}

}  // namespace

std::vector<Maaf6Component> maaf6_pair_components(const Maaf6Wedge &w, int pairs) {
    check_wedge(w, pairs);
    std::vector<Maaf6Component> out(static_cast<std::size_t>(pairs));
    for (int p = 0; p < pairs; ++p) out[std::size_t(p)].index = p;
    const double u_abs_min = std::min(std::fabs(w.u_min), std::fabs(w.u_max));
    const double u_abs_max = std::max(std::fabs(w.u_min), std::fabs(w.u_max));
    if (w.has_y) {
        // MAAF Sec. 6.2, the "simple optimization": the x band every wedge allows.
        double omega_x = w.omega_x_max;
        if (one_signed(w)) omega_x = std::min(omega_x, w.omega_u_max / u_abs_min);
        const std::vector<MaafComponent> xy =
            maaf_pair_components(w.y_min, w.y_max, omega_x, w.omega_y_max, pairs);
        for (int p = 0; p < pairs; ++p) {
            const MaafComponent &c = xy[std::size_t(p)];
            Maaf6Component &o = out[std::size_t(p)];
            o.centre_x = c.centre_x;
            o.sigma_x = c.sigma_x;
            o.centre_y = c.centre_y;
            o.sigma_y = c.sigma_y;
            o.weight = c.weight;
            if (!w.has_u) continue;
            // MAAF Fig. 11(c): the component's x range mapped through the u-wedge, Omega_u = s_u Omega_x.
            const double a = c.centre_x - c.sigma_x, b = c.centre_x + c.sigma_x;
            const double products[4] = {w.u_min * a, w.u_min * b, w.u_max * a, w.u_max * b};
            const double lo = std::max(-w.omega_u_max, *std::min_element(products, products + 4));
            const double hi = std::min(w.omega_u_max, *std::max_element(products, products + 4));
            o.centre_u =
                hi > lo ? 0.5 * (lo + hi) : std::clamp(0.5 * (lo + hi), -w.omega_u_max, w.omega_u_max);
            o.sigma_u = hi > lo ? 0.5 * (hi - lo) : 0.0;
        }
        return out;
    }
    if (one_signed(w)) {
        // No y-wedge: a 2D MAAF over (x, u), the u axis partitioned as MAAF Eq. 6-10 partition y.
        const double sign = w.u_min > 0 ? 1.0 : -1.0;
        const std::vector<MaafComponent> xu =
            maaf_pair_components(u_abs_min, u_abs_max, w.omega_x_max, w.omega_u_max, pairs);
        for (int p = 0; p < pairs; ++p) {
            const MaafComponent &c = xu[std::size_t(p)];
            Maaf6Component &o = out[std::size_t(p)];
            o.centre_x = c.centre_x;
            o.sigma_x = c.sigma_x;
            o.centre_u = sign * c.centre_y;  // Omega_u = s_u Omega_x with s_u < 0 flips the u centre
            o.sigma_u = c.sigma_y;
            o.weight = c.weight;
        }
        return out;
    }
    // The focal-plane box (u slopes of both signs) or no wedge at all: the
    // central axis-aligned filter at the pixel band (MAAF Sec. 6.2).
    out[0].sigma_x = w.omega_x_max;
    out[0].weight = 1.0;
    return out;
}

namespace {

/// maaf6_partition_check() of `components`, maaf6_pair_components(w, pairs).
Maaf6PartitionCheck partition_check(const Maaf6Wedge &w, int pairs, double k, double window_m,
                                    const std::vector<Maaf6Component> &components) {
    Maaf6PartitionCheck check;
    if (pairs == 1) return check;
    // The x band the partition was cut to, as maaf6_pair_components() computes it.
    const double u_abs_min = std::min(std::fabs(w.u_min), std::fabs(w.u_max));
    double band_x = w.omega_x_max;
    if (w.has_y && one_signed(w)) band_x = std::min(band_x, w.omega_u_max / u_abs_min);
    check.band_clipped = w.has_y ? w.omega_y_max >= w.y_min * band_x
                                 : !one_signed(w) || w.omega_u_max >= u_abs_min * w.omega_x_max;
    check.beyond_window = !(3.0 * k < components[0].sigma_x * window_m);  // 3 k / sigma_x^0 > window
    // The focal-plane box (MAAF Sec. 6.2): the u-wedge straddles 0, so there is no
    // one-signed wedge to pack; the pixel gets extra samples instead (measured on room:
    // the partition there tripled the direct layer's error, see maaf6.h).
    check.focal_box = w.has_u && !one_signed(w);
    return check;
}

}  // namespace

Maaf6PartitionCheck maaf6_partition_check(const Maaf6Wedge &w, int pairs, double k, double window_m) {
    return partition_check(w, pairs, k, window_m, maaf6_pair_components(w, pairs));
}

std::vector<Maaf6Component> maaf6_filter_components(const Maaf6Wedge &w, int pairs, double k,
                                                    double window_m) {
    std::vector<Maaf6Component> out = maaf6_pair_components(w, pairs);
    if (partition_check(w, pairs, k, window_m, out).partition_used()) return out;
    const Maaf6Component central = maaf6_pair_components(w, 1)[0];  // MYRD14's axis-aligned filter
    for (Maaf6Component &c : out) c.weight = 0;
    out[0] = central;
    return out;
}

double maaf6_lens_band(const Maaf6Wedge &w) {
    check_wedge(w, 1);
    if (!one_signed(w)) return 0.0;
    const double band = w.omega_u_max / std::min(std::fabs(w.u_min), std::fabs(w.u_max));
    return band < w.omega_x_max ? band : 0.0;
}

double maaf6_light_attenuation(double centre_y, double omega_y_max) {
    if (!(omega_y_max > 0) || !std::isfinite(omega_y_max))
        throw Error("MAAF 6D: the y band must be positive and finite");
    const double t = centre_y / (0.5 * omega_y_max);  // sigma C_y with Omega_y^max = 2 / sigma (MAAF Sec. 3)
    return std::exp(-0.5 * t * t);
}

int maaf6_channel_count(int pairs) {
    return (2 * pairs - 1) * (2 * pairs - 1);
}

Maaf6SampleSide::Maaf6SampleSide(const std::vector<Maaf6Component> &pairs) {
    if (pairs.empty() || pairs.size() > centre_y_.size())
        throw Error("MAAF 6D sample side: between 1 and 8 pairs");
    pairs_ = int(pairs.size());
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        centre_y_[p] = pairs[p].centre_y;
        centre_u_[p] = pairs[p].centre_u;
    }
}

void Maaf6SampleSide::evaluate(double y, double u, double *phi) const {
    phi[0] = 1.0;
    for (int p = 1; p < pairs_; ++p) {
        const double phase = centre_y_[std::size_t(p)] * y + centre_u_[std::size_t(p)] * u;  // MAAF Eq. 23
        phi[2 * p - 1] = std::cos(phase);
        phi[2 * p] = std::sin(phase);
    }
}

void Maaf6SampleSide::accumulate(double y1, double u1, double y2, double u2, const float value[3],
                                 double weight, double *rgb_sums, double *weight_sums) const {
    const int n = 2 * pairs_ - 1;
    double phi1[16], phi2[16];
    evaluate(y1, u1, phi1);  // each subspace with its own coordinates
    evaluate(y2, u2, phi2);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const int c = a * n + b;
            const double side = phi1[a] * phi2[b];  // the 6D filter as the product of two 3D ones
            weight_sums[c] += weight * side;
            for (int k = 0; k < 3; ++k) rgb_sums[3 * c + k] += double(value[k]) * side;
        }
}

Maaf6XKernel::Maaf6XKernel(const std::vector<Maaf6Component> &pairs, double k) : k_(k) {
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        const Maaf6Component &c = pairs[p];
        // The DC of cos(C_x dx) g(dx; k / sigma_x): the pair's kernel is made zero-mean (see maaf6.h).
        const double dc_ratio = c.sigma_x > 0 ? c.centre_x * k / c.sigma_x : 0.0;
        const double dc = p > 0 && c.sigma_x > 0 ? std::exp(-0.5 * dc_ratio * dc_ratio) : 0.0;
        pairs_.push_back({c.sigma_x, c.centre_x, c.weight, dc});
    }
}

void Maaf6XKernel::operator()(double dx_m, double *kernel) const {
    for (std::size_t p = 0; p < pairs_.size(); ++p) {
        const Pair &c = pairs_[p];
        // Primal std k / sigma_x metres; sigma_x = 0 would be an infinitely wide kernel: constant.
        const double t = dx_m * c.sigma_x / k_;
        const double envelope = std::exp(-0.5 * t * t);
        if (p == 0) {
            kernel[0] = envelope;  // MAAF Eq. 22, the central term
            continue;
        }
        const double phase = c.centre_x * dx_m;
        kernel[2 * p - 1] = 2.0 * c.weight * (std::cos(phase) - c.dc) * envelope;  // MAAF Eq. 13, cos x cos
        kernel[2 * p] = -2.0 * c.weight * std::sin(phase) * envelope;              // MAAF Eq. 13, - sin x sin
    }
}

void maaf6_x_kernel(const std::vector<Maaf6Component> &pairs, double k, double dx_m, double *kernel) {
    Maaf6XKernel(pairs, k)(dx_m, kernel);
}

}  // namespace aaf

namespace aaf {

void maaf6_tangent_frame(Vec3 n, Vec3 light_axis_u, Vec3 light_axis_v, Vec3 &t1, Vec3 &t2) {
    Vec3 axis = light_axis_u - n * dot(n, light_axis_u);
    if (length(axis) < 0.42f) axis = light_axis_v - n * dot(n, light_axis_v);  // sin 25 degrees
    if (length(axis) < 1e-6f) axis = std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    t1 = normalize(axis - n * dot(n, axis));
    t2 = cross(n, t1);
}

}  // namespace aaf
