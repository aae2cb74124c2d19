#include "aaf/core/methods/maaf/maaf_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "aaf/core/kernels/gather.h"
#include "aaf/core/methods/maaf/maaf_accumulation.h"
#include "aaf/core/methods/maaf/maaf_components.h"
#include "aaf/core/methods/maaf/maaf_separable.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

/// Taps stop at 3 standard deviations of a component's x-side Gaussian.
constexpr double kCutoffSigmas = 3.0;

void check_size(ConstPlaneView view, int width, int height, const std::string &what) {
    if (!view.valid() || view.width != width || view.height != height)
        throw Error("MAAF input '" + what + "' is missing or has another size");
}

void check_inputs(const MaafInputs &in, const LightPlane &light, const MaafParams &params) {
    params.validate();
    light.validate();
    if (in.pairs < 1 || in.pairs > kMaafMaxPairs)
        throw Error("MAAF sums: N must lie in [1, " + std::to_string(kMaafMaxPairs) + "]");
    if (params.pairs_used != 0 && params.pairs_used != 1 && params.pairs_used != in.pairs)
        throw Error("MAAF can use all " + std::to_string(in.pairs) +
                    " filter pairs of its sums or the central filter alone (1), not " +
                    std::to_string(params.pairs_used));
    const int width = in.pixel_size.width, height = in.pixel_size.height;
    if (width <= 0 || height <= 0) throw Error("MAAF input 'pixel_size' is missing or empty");
    const std::size_t channels = std::size_t(maaf_channel_count(in.pairs));
    if (in.value_sums.size() != channels || in.unoccluded_sums.size() != channels)
        throw Error("MAAF needs " + std::to_string(channels) +
                    " value and unoccluded sums for N = " + std::to_string(in.pairs));
    for (std::size_t c = 0; c < channels; ++c) {
        check_size(in.value_sums[c], width, height, "maaf value sum " + std::to_string(c));
        check_size(in.unoccluded_sums[c], width, height, "maaf unoccluded sum " + std::to_string(c));
    }
    check_size(in.s_min, width, height, "maaf s_min");
    check_size(in.s_max, width, height, "maaf s_max");
    check_size(in.omega_x_max, width, height, "maaf omega_x_max");
    if (in.window_s_min.valid() || in.window_s_max.valid()) {
        check_size(in.window_s_min, width, height, "maaf window s_min");
        check_size(in.window_s_max, width, height, "maaf window s_max");
    }
    for (int c = 0; c < 3; ++c) {
        check_size(in.position[std::size_t(c)], width, height, "position");
        check_size(in.normal[std::size_t(c)], width, height, "normal");
    }
    check_size(in.object_id, width, height, "object_id");
    if (in.samples.valid()) check_size(in.samples, width, height, "spp");
}

/// True when the stored wedge is one maaf_components() accepts.
bool usable_wedge(float s_min, float s_max, float omega_x_max, float pixel_size) {
    return s_min >= 0 && s_max >= s_min && std::isfinite(s_max) && omega_x_max > 0 &&
           std::isfinite(omega_x_max) && pixel_size > 0 && std::isfinite(pixel_size);
}

/// How much pixel (x, y)'s bands widen for its samples (MaafParams::band_spp): 1 at or below band_spp.
double band_widening(const MaafInputs &in, const MaafParams &params, int x, int y) {
    if (!(params.band_spp > 0) || !in.samples.valid()) return 1.0;
    const double samples = double(in.samples(x, y));
    return std::isfinite(samples) && samples > params.band_spp ? std::sqrt(samples / params.band_spp) : 1.0;
}

/// What MaafParams::pair_weights needs, built once per filter.
struct PairWeights {
    MaafPairWeights kind = MaafPairWeights::Eq10;
    std::unique_ptr<SampleSpectrum> spectrum;         ///< Light: the light's density's
    std::shared_ptr<const MaafFittedWeights> fitted;  ///< Fitted: the table for the light's band

    PairWeights(const MaafParams &params, int pairs) : kind(params.pair_weights) {
        SampleDensity density = params.light_density;
        if (density.half_width == 0) density.half_width = 2.0 / params.omega_y_max_rad_per_m;
        if (kind == MaafPairWeights::Light) spectrum = std::make_unique<SampleSpectrum>(density);
        if (kind == MaafPairWeights::Fitted && pairs > 1)
            fitted = shared_fitted_weights(density, params.omega_y_max_rad_per_m, pairs, params.k,
                                           MaafKernelForm::Maaf4D);
    }

    /// mu_p of each of `components` (pairs p = 0 ..) of a wedge of slopes s_min, s_max; `clipped`:
    /// the pixel band lowered its Omega_y^max.
    void apply(std::vector<MaafComponent> &components, double s_min, double s_max, bool clipped) const {
        if (components.size() < 2) return;
        switch (kind) {
            case MaafPairWeights::Eq10:
                return;
            case MaafPairWeights::One:
                for (MaafComponent &c : components) c.weight = 1.0;
                return;
            case MaafPairWeights::Light:
                for (MaafComponent &c : components) c.weight *= (*spectrum)(c.centre_y);
                return;
            case MaafPairWeights::Fitted: {
                if (clipped) return;  // the table is for the light's own band
                double mu[kMaafMaxPairs];
                fitted->weights(s_max > 0 ? s_min / s_max : 1.0, mu);
                for (std::size_t p = 1; p < components.size(); ++p) components[p].weight = mu[p - 1];
                return;
            }
        }
    }
};

/// The slopes pixel (x, y) of wedge [s_min, s_max] is filtered with: the
/// window's (MaafInputs::window_s_min) where they partition the same
/// Omega_y^max at these bands (the offset pairs' centres 2p Omega / (2N - 1),
/// the phases the sums carry: MAAF Eq. 6) or only the central filter is
/// used, so that the widths hold still from frame to frame; else its own.
std::pair<double, double> filter_slopes(const MaafInputs &in, int x, int y, double s_min, double s_max,
                                        double band_x, double band_y, int used) {
    if (!in.window_s_min.valid() || !in.window_s_max.valid()) return {s_min, s_max};
    const float window_lo = in.window_s_min(x, y), window_hi = in.window_s_max(x, y);
    if (!(window_lo >= 0) || !std::isfinite(window_hi)) return {s_min, s_max};
    const double lo = std::min(s_min, double(window_lo)), hi = std::max(s_max, double(window_hi));
    if (used == 1 || maaf_partitioned_omega_y_max(lo, hi, band_x, band_y) ==
                         maaf_partitioned_omega_y_max(s_min, s_max, band_x, band_y))
        return {lo, hi};
    return {s_min, s_max};
}

MaafPixelKernel pixel_kernels(const MaafInputs &in, const MaafParams &params, const PairWeights &weights,
                              int pairs, int x, int y) {
    MaafPixelKernel k;
    const float s_min = in.s_min(x, y), s_max = in.s_max(x, y), omega_x_max = in.omega_x_max(x, y);
    const float pixel_size = in.pixel_size(x, y);
    if (in.object_id(x, y) == 0 || !usable_wedge(s_min, s_max, omega_x_max, pixel_size)) return k;
    // AAF Sec. 5.2's consistency: past band_spp samples both bands widen as the square root of the
    // samples (the pixel band too, or a wedge it clips would keep its width), and the central filter
    // alone is used: the offset pairs' phases were accumulated at the render's bands. Its other
    // components keep weight 0 and radius 0.
    const double widening = band_widening(in, params, x, y);
    const int used = widening > 1 ? 1 : pairs;
    const double band_x = widening * double(omega_x_max), band_y = widening * params.omega_y_max_rad_per_m;
    const auto [lo, hi] = filter_slopes(in, x, y, s_min, s_max, band_x, band_y, used);
    std::vector<MaafComponent> components = maaf_pair_components(lo, hi, band_x, band_y, used);
    weights.apply(components, lo, hi, maaf_partitioned_omega_y_max(lo, hi, band_x, band_y) < band_y);
    for (int p = 0; p < used; ++p) {
        const MaafComponent &c = components[std::size_t(p)];
        // The Fourier Gaussian's std is k sigma_x^p (MaafParams::k; the paper's reading is k = 1).
        const double fourier_sigma = params.k * c.sigma_x;
        const double sigma_m = 1.0 / fourier_sigma;  // primal width of G(.; k sigma_x) (MAAF Eq. 12)
        const double radius =
            std::min(std::ceil(kCutoffSigmas * sigma_m / pixel_size), double(params.max_radius_px));
        k.omega_x[p] = float(c.centre_x);
        k.inv_two_sigma_sq[p] =
            float(std::min(0.5 * fourier_sigma * fourier_sigma, double(std::numeric_limits<float>::max())));
        k.radius_px[p] = int(radius);
        k.weight[p] = (p == 0 ? 1.0 : 2.0) * c.weight * c.sigma_x;  // MAAF Eq. 21
    }
    k.filtered = true;
    return k;
}

/// The light-side functions of component p (maaf_accumulation.h's indices) with their x-side modulation.
struct Function {
    int index;
    AxisModulation::Kind kind;
};
std::vector<Function> functions_of(int p) {
    if (p == 0) return {{0, AxisModulation::Kind::None}};
    // MAAF Eq. 21 with the tap's displacement from the centre: cos(C_x d) for h_c, -sin(C_x d) for h_s.
    return {{2 * p - 1, AxisModulation::Kind::Cos}, {2 * p, AxisModulation::Kind::NegSin}};
}

/// Adds one component pair's filtered sums, weighted (MAAF Eq. 21), to the
/// totals; the central pair's (pu = pv = 0) are also kept on their own.
void add_pair_sums(const std::vector<MaafPixelKernel> &kernels, int pu, int pv,
                   const std::vector<float> &value, const std::vector<float> &unoccluded,
                   MaafFilteredSums &sums) {
    for (std::size_t i = 0; i < kernels.size(); ++i) {
        if (!kernels[i].filtered) continue;
        const double w = kernels[i].weight[pu] * kernels[i].weight[pv];
        sums.numerator[i] += w * value[i];
        sums.denominator[i] += w * unoccluded[i];
        if (pu == 0 && pv == 0) {
            sums.central_numerator[i] = value[i];
            sums.central_denominator[i] = unoccluded[i];
        }
    }
}

/// The gather's guides (coordinates along the light's axes, unit normals,
/// object ids) and every pixel's component kernels (`kernels`, row-major).
GatherGuides maaf_guides(const MaafInputs &in, const LightPlane &light, const MaafParams &params, int pairs,
                         std::vector<MaafPixelKernel> &kernels) {
    const PairWeights weights(params, pairs);
    const int width = in.pixel_size.width, height = in.pixel_size.height;
    GatherGuides guides;
    guides.resize(width, height);
    kernels.assign(std::size_t(width) * std::size_t(height), MaafPixelKernel{});
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = guides.index(x, y);
            // Signed displacements along the light's own axes (NOTES-MAAF: the cos/sin phases need them).
            const Vec3 p{in.position[0](x, y), in.position[1](x, y), in.position[2](x, y)};
            const float u = dot(light.axis_u, p - light.center), v = dot(light.axis_v, p - light.center);
            if (!std::isfinite(u + v)) {
                guides.object_id[i] = std::numeric_limits<float>::quiet_NaN();  // never a tap
                continue;
            }
            guides.coord_u_m[i] = u;
            guides.coord_v_m[i] = v;
            const Vec3 n{in.normal[0](x, y), in.normal[1](x, y), in.normal[2](x, y)};
            const float len = length(n);
            const Vec3 unit = (len > 0 && std::isfinite(len)) ? n / len : Vec3{};
            guides.normal_x[i] = unit.x;
            guides.normal_y[i] = unit.y;
            guides.normal_z[i] = unit.z;
            guides.object_id[i] = in.object_id(x, y);
            kernels[i] = pixel_kernels(in, params, weights, pairs, x, y);
        }
    });
    return guides;
}

/// `view` in the guides' row-major layout, non-finite values as 0.
std::vector<float> finite_copy(ConstPlaneView view, const GatherGuides &guides) {
    std::vector<float> plane(std::size_t(guides.width) * std::size_t(guides.height));
    parallel_for_rows(guides.height, [&](int y) {
        for (int x = 0; x < guides.width; ++x) {
            const float value = view(x, y);
            plane[guides.index(x, y)] = std::isfinite(value) ? value : 0.0f;
        }
    });
    return plane;
}

/// maaf_separable_filter()'s sums by the full-window gather: for each pair of
/// components (pu along the light's first axis, pv along its second; MAAF
/// Fig. 7) each of its channels through gather_modulated(), then weighted
/// (MAAF Eq. 21) into the totals. Sets the guides' radius_px per pair.
MaafFilteredSums full_window_filter(GatherGuides &guides, float normal_threshold_deg,
                                    const std::vector<MaafPixelKernel> &kernels, int sum_pairs, int pairs,
                                    const std::vector<std::vector<float>> &values,
                                    const std::vector<std::vector<float>> &unoccludeds) {
    const int width = guides.width, height = guides.height;
    const std::size_t count = kernels.size();
    const int per_axis = maaf_functions_per_axis(sum_pairs);
    MaafFilteredSums sums{std::vector<double>(count, 0.0), std::vector<double>(count, 0.0),
                          std::vector<double>(count, 0.0), std::vector<double>(count, 0.0)};
    GatherSettings settings;
    settings.normal_threshold_deg = normal_threshold_deg;
    settings.mode = GatherMode::Full2D;
    for (int pu = 0; pu < pairs; ++pu)
        for (int pv = 0; pv < pairs; ++pv) {
            std::vector<float> omega_u(count), omega_v(count), inv_u(count), inv_v(count), out_value(count),
                out_unoccluded(count);
            for (std::size_t i = 0; i < count; ++i) {
                const MaafPixelKernel &k = kernels[i];
                guides.radius_px[i] = k.filtered ? std::max(k.radius_px[pu], k.radius_px[pv]) : 0;
                omega_u[i] = k.omega_x[pu];
                omega_v[i] = k.omega_x[pv];
                inv_u[i] = k.inv_two_sigma_sq[pu];
                inv_v[i] = k.inv_two_sigma_sq[pv];
            }
            for (const Function &fu : functions_of(pu))
                for (const Function &fv : functions_of(pv)) {
                    const std::size_t c = std::size_t(fu.index * per_axis + fv.index);
                    const AxisModulation along_u{fu.kind,
                                                 plane_view<const float>(omega_u.data(), width, height),
                                                 plane_view<const float>(inv_u.data(), width, height)};
                    const AxisModulation along_v{fv.kind,
                                                 plane_view<const float>(omega_v.data(), width, height),
                                                 plane_view<const float>(inv_v.data(), width, height)};
                    gather_modulated(guides, settings,
                                     {plane_view<const float>(values[c].data(), width, height),
                                      plane_view<const float>(unoccludeds[c].data(), width, height)},
                                     {plane_view(out_value.data(), width, height),
                                      plane_view(out_unoccluded.data(), width, height)},
                                     along_u, along_v, GatherNormalisation::None);
                    add_pair_sums(kernels, pu, pv, out_value, out_unoccluded, sums);
                }
        }
    return sums;
}

}  // namespace

void MaafParams::validate() const {
    if (!(omega_y_max_rad_per_m > 0) || !std::isfinite(omega_y_max_rad_per_m))
        throw Error("MAAF Omega_y^max must be positive and finite");
    if (pairs_used < 0) throw Error("MAAF filter pairs must be >= 0");
    if (!(normal_threshold_deg >= 0 && normal_threshold_deg <= 180))
        throw Error("MAAF normal threshold must lie in [0, 180] degrees");
    if (max_radius_px < 0) throw Error("MAAF maximum filter radius must be >= 0 pixels");
    if (!(k > 0) || !std::isfinite(k)) throw Error("MAAF width scale k must be positive and finite");
    if (!(band_spp >= 0) || !std::isfinite(band_spp)) throw Error("MAAF band spp must be >= 0 and finite");
}

void maaf_filter(const MaafInputs &in, const LightPlane &light, const MaafParams &params, PlaneView out) {
    check_inputs(in, light, params);
    const int width = in.pixel_size.width, height = in.pixel_size.height;
    if (!out.valid() || out.width != width || out.height != height)
        throw Error("MAAF output 'filtered visibility' is missing or has another size");
    const int pairs = params.pairs_used == 0 ? in.pairs : params.pairs_used;

    std::vector<MaafPixelKernel> kernels;
    GatherGuides guides = maaf_guides(in, light, params, pairs, kernels);
    // Non-finite sums (a renderer's NaN) are read as 0, so they cannot spread through the filter.
    std::vector<std::vector<float>> values, unoccludeds;
    for (std::size_t c = 0; c < in.value_sums.size(); ++c) {
        values.push_back(finite_copy(in.value_sums[c], guides));
        unoccludeds.push_back(finite_copy(in.unoccluded_sums[c], guides));
    }
    const MaafFilteredSums sums = params.separable
                                      ? maaf_separable_filter(guides, params.normal_threshold_deg, kernels,
                                                              in.pairs, pairs, values, unoccludeds)
                                      : full_window_filter(guides, params.normal_threshold_deg, kernels,
                                                           in.pairs, pairs, values, unoccludeds);

    const std::vector<float> &value0 = values[0], &unoccluded0 = unoccludeds[0];
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = guides.index(x, y);
            // Unfiltered: the pixel's own light-weighted visibility, 1 without samples.
            double result = unoccluded0[i] > 0 ? double(value0[i]) / double(unoccluded0[i]) : 1.0;
            if (kernels[i].filtered) {
                const double numerator = sums.numerator[i], denominator = sums.denominator[i];
                if (denominator > 0 && std::isfinite(numerator / denominator))
                    result = numerator / denominator;
                else if (sums.central_denominator[i] > 0)  // the central filter alone (AAF)
                    result = sums.central_numerator[i] / sums.central_denominator[i];
            }
            out(x, y) = std::isfinite(result) ? float(result) : 0.0f;
        }
    });
}

}  // namespace aaf
