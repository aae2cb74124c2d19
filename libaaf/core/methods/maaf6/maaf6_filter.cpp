#include "aaf/core/methods/maaf6/maaf6_filter.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "aaf/core/methods/maaf/maaf_accumulation.h"
#include "aaf/core/methods/maaf6/maaf6_components.h"
#include "aaf/core/methods/maaf6/maaf6_rows.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3 read3(const std::array<ConstPlaneView, 3> &v, int x, int y) {
    return {v[0](x, y), v[1](x, y), v[2](x, y)};
}

/// The offset pairs' cos and sin kernels cancel (pass nothing at Omega_x = 0,
/// and nothing odd) only over a whole window. Where the guides (other
/// normals, background) or the image's border take away more than this share
/// of the central envelope's mass, the pixel gets the axis-aligned filter.
/// Measured on room at 160x120, 16 and 128 spp, every effect alone and
/// together: 0.7, 0.8, 0.9, 0.97 all brought N = 3 to within 0-5% of N = 1
/// where it had been up to 28% worse (indirect at 128 spp); 0.8 was the best at 16 spp.
constexpr double kMinWindowMass = 0.8;

/// A Gaussian of std_m metres of a tap's displacement d on the pixel's
/// frame (t1, t2 and the off-plane distance, AAF's world distance).
double frame_gaussian(const Vec3 &d, double std_m) {
    return std::exp(-0.5 * double(dot(d, d)) / (std_m * std_m));
}

/// Whether the tap (tx, ty) enters the filter of a pixel of normal n: a hit
/// with samples whose normal turns less than the threshold (MAAF Sec. 6.2).
bool tap_accepted(const Maaf6SharedInputs &shared, Vec3 n, double cos_threshold, int tx, int ty) {
    if (shared.object_id(tx, ty) == 0 || !(shared.samples(tx, ty) > 0)) return false;
    const Vec3 nt = read3(shared.normal, tx, ty);
    const float len = length(nt);
    return len > 0 && double(dot(n, nt)) >= cos_threshold * double(len);
}

/// The central envelope exp(-i^2 / 2 std_px^2) for i = 0..r pixels into
/// `envelope`; returns its mass over the whole (2r + 1)^2 window.
double window_envelope(double std_px, int r, std::vector<double> &envelope) {
    envelope.resize(std::size_t(r) + 1);
    double line = 0;
    for (int i = 0; i <= r; ++i) {
        envelope[std::size_t(i)] = std::exp(-0.5 * double(i * i) / (std_px * std_px));
        line += (i == 0 ? 1.0 : 2.0) * envelope[std::size_t(i)];
    }
    return line * line;
}

/// The window of maaf6_filter_layer() around (x, y) for a central std of std_m.
int window_radius(const Maaf6SharedInputs &shared, const Maaf6FilterParams &params, int x, int y,
                  double std_m) {
    const double reach_px = 3.0 * std_m / std::max(1e-12, double(shared.pixel_size(x, y)));
    return int(std::min(double(params.max_radius_px), std::ceil(reach_px)));
}

void check(const ConstPlaneView &v, int width, int height, const char *what) {
    if (!v.valid() || v.width != width || v.height != height)
        throw Error(std::string("MAAF 6D input '") + what + "' is missing or has another size");
}

/// Whether pixel (x, y)'s bands are widened (Maaf6FilterParams::band_spp).
bool band_widened(const Maaf6SharedInputs &shared, const Maaf6FilterParams &params, int x, int y) {
    return params.band_spp > 0 && double(shared.samples(x, y)) > params.band_spp;
}

/// The pairs pixel (x, y) is filtered with: 1 where its bands are widened.
/// The stored sums carry the phases cos / sin(C_y^p y + C_u^p u) of the
/// partition at the render's bands; a widened band would move every C_y^p and
/// C_u^p, which the sums cannot follow, and pairs with widened x centres and
/// the stored phases sit off the wedge (room, converged shadows, --band-spp 64:
/// N = 3 0.0090 against N = 1 0.0025). The axis-aligned filter needs no phase.
int pixel_pairs(const Maaf6SharedInputs &shared, const Maaf6FilterParams &params, int x, int y) {
    return band_widened(shared, params, x, y) ? 1 : params.pairs_used;
}

/// The wedge of pixel (x, y) of a hit; false where there is none to filter
/// along (no y-wedge and no one-signed u-wedge, or no finite positive pixel band).
bool pixel_wedge(const Maaf6LayerInputs &layer, const Maaf6SharedInputs &shared,
                 const Maaf6FilterParams &params, int x, int y, Maaf6Wedge &wedge) {
    // Non-finite inputs (a broken pixel) count as no wedge: they stay in their own pixel.
    wedge.has_y = layer.y_max(x, y) >= 0 && layer.y_min(x, y) >= 0 && std::isfinite(layer.y_max(x, y)) &&
                  layer.y_max(x, y) >= layer.y_min(x, y);
    wedge.y_min = wedge.has_y ? double(layer.y_min(x, y)) : 0.0;
    wedge.y_max = wedge.has_y ? double(layer.y_max(x, y)) : 0.0;
    // AAF Sec. 5.2's consistency: the bands widen as sqrt(n / band_spp) past band_spp samples.
    const double samples = double(shared.samples(x, y));
    const double widening = band_widened(shared, params, x, y) ? std::sqrt(samples / params.band_spp) : 1.0;
    wedge.omega_y_max = layer.omega_y_max * widening;
    wedge.has_u = shared.omega_u_max > 0 && std::isfinite(shared.u_min(x, y)) &&
                  std::isfinite(shared.u_max(x, y)) && shared.u_max(x, y) >= shared.u_min(x, y);
    wedge.u_min = double(shared.u_min(x, y));
    wedge.u_max = double(shared.u_max(x, y));
    wedge.omega_u_max = shared.omega_u_max * widening;
    // The pixel band widens too: it bounds the filter at the render's sampling rate, and with it
    // fixed a wedge clipped by it would keep blurring over the neighbours whatever the samples
    // (room, shadows alone at 48x36: 0.0109 at 64 spp, 0.0107 at 256).
    wedge.omega_x_max = double(shared.omega_x(x, y)) * widening;
    if (!(wedge.omega_x_max > 0 && std::isfinite(wedge.omega_x_max))) return false;
    if (wedge.has_y) return true;
    // Only a u-wedge: filtered where it is one-signed and narrower than the pixel band.
    // Clipped by the pixel band (a circle of confusion of about a pixel or less),
    // the filter would be the pixel band's own, which only blurs: the lens
    // samples vary over less than it, so there is no noise for it to remove.
    return maaf6_lens_band(wedge) > 0;
}

void check_inputs(const Maaf6LayerInputs &layer, const Maaf6SharedInputs &shared,
                  const Maaf6FilterParams &params) {
    const int width = shared.object_id.width, height = shared.object_id.height;
    const int stored_n = 2 * params.stored_pairs - 1;
    if (params.pairs_used != 1 && params.pairs_used != params.stored_pairs)
        throw Error("MAAF 6D: the filter uses all stored pairs or 1");
    if (int(layer.sums.size()) != 3 * stored_n * stored_n || int(layer.weights.size()) != stored_n * stored_n)
        throw Error("MAAF 6D: a layer needs 3 (2N-1)^2 sums and (2N-1)^2 weights");
    for (const ConstPlaneView &v : layer.sums) check(v, width, height, "sums");
    for (const ConstPlaneView &v : layer.weights) check(v, width, height, "weights");
    check(layer.y_min, width, height, "ymin");
    check(layer.y_max, width, height, "ymax");
    check(shared.u_min, width, height, "umin");
    check(shared.u_max, width, height, "umax");
    check(shared.omega_x, width, height, "omegax");
    check(shared.pixel_size, width, height, "pixel_size");
    check(shared.samples, width, height, "spp");
    for (int c = 0; c < 3; ++c) {
        check(shared.position[std::size_t(c)], width, height, "position");
        check(shared.normal[std::size_t(c)], width, height, "normal");
    }
    if (!(params.k > 0)) throw Error("MAAF 6D: k must be positive");
}

/// What a filtered pixel's taps share: its components, its frame and windows.
struct PixelFilter {
    std::vector<Maaf6Component> pairs;             ///< only the central one where the offsets weigh 0
    std::vector<Maaf6Component> axis_aligned;      ///< N = 1's (MYRD14's), beside the partition
    Maaf6XKernel x_kernel, axis_aligned_x_kernel;  ///< their x kernels (maaf6_x_kernel)
    bool offsets_used = false;
    int pixel_n = 1;    ///< the channels per axis gathered: 2N - 1, or 1 without offsets
    Vec3 p, n, t1, t2;  ///< the pixel's position, unit normal and tangent frame
    double std_m = 0, axis_aligned_std_m = 0, lens_std_m = 0;
    int r = 0, axis_aligned_r = 0;  ///< the windows' radii, pixels
    double mass_all = 0;            ///< the central envelope's mass over the whole window
};

/// A pixel's sums over its accepted taps.
struct TapSums {
    double num[3] = {0, 0, 0}, den = 0;         ///< the filter's (the partition's with offsets)
    double num0[3] = {0, 0, 0}, den0 = 0;       ///< the central term alone
    double num1[3] = {0, 0, 0}, den1 = 0;       ///< the axis-aligned filter over its own window
    double unoccluded = 0, unoccluded_den = 0;  ///< the unoccluded light through the lens band
    double mass_kept = 0;                       ///< the central envelope's mass the guides keep
};

/// maaf6_filter_layer() for one layer: per row, each pixel's components,
/// then its taps' sums, then the filtered ratio times the unoccluded light.
class LayerFilter {
  public:
    LayerFilter(const Maaf6LayerInputs &layer, const Maaf6SharedInputs &shared, const LightPlane &light,
                const Maaf6FilterParams &params)
        : layer_(layer),
          shared_(shared),
          light_(light),
          params_(params),
          stored_n_(2 * params.stored_pairs - 1),
          used_n_(2 * params.pairs_used - 1),
          cos_threshold_(std::cos(double(params.normal_threshold_deg) * kPi / 180.0)) {
        if (params.vectorised && params.stored_pairs == 3) prepare_taps();
        // The fitted pair weights' tables (MaafFittedWeights): the y-wedge's and the lens wedge's.
        if (params.pair_weights == Maaf6PairWeights::Fitted && params.pairs_used > 1) {
            const int n = params.pairs_used;
            fitted_y_ = shared_fitted_weights(layer.y_density, layer.omega_y_max, n, params.k);
            if (shared.omega_u_max > 0)
                fitted_u_ = shared_fitted_weights(shared.lens_density, shared.omega_u_max, n, params.k);
        }
    }

    /// Filters row y into `out`; its buffers are the row's own (rows run in parallel).
    void row(int y, const std::array<PlaneView, 3> &out) const {
        const int width = shared_.object_id.width;
        const int padded =
            (width + detail::kMaaf6RowPadding - 1) / detail::kMaaf6RowPadding * detail::kMaaf6RowPadding;
        std::vector<std::optional<PixelFilter>> filters(static_cast<std::size_t>(width));
        std::vector<double> envelope_px;  // the central envelope per pixel offset, for the window's mass
        std::vector<float> params;
        if (taps_) {
            params.assign(std::size_t(detail::kCentreFieldCount) * std::size_t(padded), 0.0f);
            std::fill_n(params.begin() + std::ptrdiff_t(detail::kCentreRadius) * padded, padded, -1.0f);
        }
        for (int x = 0; x < width; ++x) {
            Maaf6Wedge wedge;
            // No wedge to filter along (a pinhole without y-wedge, or the focal-plane box):
            // the pixel band is the pixel itself; MAAF Sec. 6.2 adds samples there instead.
            if (shared_.object_id(x, y) == 0 || !pixel_wedge(layer_, shared_, params_, x, y, wedge)) {
                for (int c = 0; c < 3; ++c) out[std::size_t(c)](x, y) = own_mean(x, y, c);
                continue;
            }
            filters[std::size_t(x)] = pixel_filter(filter_wedge(wedge, x, y), x, y, envelope_px);
            if (taps_) centre_params(*filters[std::size_t(x)], x, y, params.data(), std::size_t(padded));
        }
        std::vector<float> vector_sums;
        if (taps_) {
            vector_sums.resize(std::size_t(detail::kSumFieldCount) * std::size_t(padded));
            detail::maaf6_row_sums(*taps_, y, padded, params.data(), std::size_t(padded), vector_sums.data());
        }
        for (int x = 0; x < width; ++x) {
            if (!filters[std::size_t(x)]) continue;
            const PixelFilter &f = *filters[std::size_t(x)];
            const TapSums sums =
                taps_ ? lane_sums(vector_sums, std::size_t(padded), x) : scalar_sums(f, x, y, envelope_px);
            finish(f, sums, x, y, out);
        }
    }

  private:
    float own_mean(int x, int y, int c) const {
        const float own_count = shared_.samples(x, y);
        return own_count > 0 ? layer_.sums[std::size_t(c)](x, y) / own_count : 0.0f;
    }

    /// Pixel (x, y)'s sums over its window, one tap at a time in double (`--filter scalar`).
    TapSums scalar_sums(const PixelFilter &f, int x, int y, std::vector<double> &envelope_px) const {
        const int width = shared_.object_id.width, height = shared_.object_id.height;
        // The central envelope per pixel offset (pixel_filter() left the row's last pixel's there).
        if (f.offsets_used)
            window_envelope(f.std_m / std::max(1e-12, double(shared_.pixel_size(x, y))), f.r, envelope_px);
        double k1[kMaafMaxPairs * 2], k2[kMaafMaxPairs * 2];
        TapSums sums;
        for (int ty = std::max(0, y - f.r); ty <= std::min(height - 1, y + f.r); ++ty)
            for (int tx = std::max(0, x - f.r); tx <= std::min(width - 1, x + f.r); ++tx)
                if (tap_accepted(shared_, f.n, cos_threshold_, tx, ty))
                    add_tap(f, x, y, tx, ty, envelope_px, k1, k2, sums);
        return sums;
    }

    /// Pixel x's sums from maaf6_row_sums().
    static TapSums lane_sums(const std::vector<float> &sums, std::size_t stride, int x) {
        const auto at = [&](int field) { return double(sums[std::size_t(field) * stride + std::size_t(x)]); };
        TapSums s;
        for (int col = 0; col < 3; ++col) {
            s.num[col] = at(detail::kSumNumR + col);
            s.num0[col] = at(detail::kSumNum0R + col);
            s.num1[col] = at(detail::kSumNum1R + col);
        }
        s.den = at(detail::kSumDen);
        s.den0 = at(detail::kSumDen0);
        s.den1 = at(detail::kSumDen1);
        s.unoccluded = at(detail::kSumUnoccluded);
        s.unoccluded_den = at(detail::kSumUnoccludedDen);
        s.mass_kept = at(detail::kSumMassKept);
        return s;
    }

    /// Pixel x's filter as maaf6_row_sums() reads it (detail::Maaf6CentreField).
    void centre_params(const PixelFilter &f, int x, int y, float *params, std::size_t stride) const {
        const auto set = [&](int field, double value) {
            params[std::size_t(field) * stride + std::size_t(x)] = float(value);
        };
        const Vec3 frame[4] = {f.p, f.n, f.t1, f.t2};
        for (int v = 0; v < 4; ++v) {
            set(detail::kCentrePx + 3 * v, frame[v].x);
            set(detail::kCentrePx + 3 * v + 1, frame[v].y);
            set(detail::kCentrePx + 3 * v + 2, frame[v].z);
        }
        const double k = params_.k;
        for (std::size_t p = 0; p < f.pairs.size(); ++p) {
            const Maaf6Component &c = f.pairs[p];
            set(detail::kCentreScale0 + int(p), c.sigma_x / k);
            if (p == 0) continue;
            set(detail::kCentreOmega1 + int(p) - 1, c.centre_x);
            set(detail::kCentreGain1 + int(p) - 1, 2.0 * c.weight);
            const double dc_ratio = c.sigma_x > 0 ? c.centre_x * k / c.sigma_x : 0.0;  // as Maaf6XKernel
            set(detail::kCentreDc1 + int(p) - 1, c.sigma_x > 0 ? std::exp(-0.5 * dc_ratio * dc_ratio) : 0.0);
        }
        set(detail::kCentreLensScale, f.lens_std_m > 0 ? 1.0 / f.lens_std_m : 0.0);
        set(detail::kCentreAxisScale, f.offsets_used ? f.axis_aligned[0].sigma_x / k : 0.0);
        set(detail::kCentreScalePixels,
            std::max(1e-12, double(shared_.pixel_size(x, y))) * f.pairs[0].sigma_x / k);
        set(detail::kCentreRadius, f.r);
        set(detail::kCentreAxisRadius, f.offsets_used ? f.axis_aligned_r : -1);
    }

    /// The filtered ratio of pixel (x, y) from its sums, times its unoccluded light, into `out`.
    void finish(const PixelFilter &f, const TapSums &sums, int x, int y,
                const std::array<PlaneView, 3> &out) const {
        const float own_count = shared_.samples(x, y);
        // The filtered ratio times the pixel's own mean weight (AAF's r(x) V(x) factoring).
        const double own_weight = own_count > 0 ? double(layer_.weights[0](x, y)) / double(own_count) : 0.0;
        const double unoccluded_mean =
            sums.unoccluded_den > 0 ? sums.unoccluded / sums.unoccluded_den : own_weight;
        // The offset components can cancel most of the normalisation: below a tenth of the
        // central term's, fall back to the central term rather than amplify noise.
        const bool partition_kept = f.offsets_used && sums.mass_kept >= kMinWindowMass * f.mass_all;
        for (int col = 0; col < 3; ++col) {
            const double own = double(own_mean(x, y, col));
            double v = f.offsets_used && !partition_kept
                           ? (sums.den1 > 1e-12 ? unoccluded_mean * sums.num1[col] / sums.den1 : own)
                       : sums.den > 0.1 * sums.den0 && sums.den0 > 1e-12
                           ? unoccluded_mean * sums.num[col] / sums.den
                       : sums.den0 > 1e-12 ? unoccluded_mean * sums.num0[col] / sums.den0
                                           : own;
            if (!std::isfinite(v)) v = own;
            v = std::max(0.0, v);  // radiance is not negative; the offset kernels' ringing can be
            out[std::size_t(col)](x, y) = float(v);
        }
    }

    /// The wedge over the temporal window (Maaf6LayerInputs::window_y_min):
    /// `own` widened to the window's slopes, of the same kind (a y-wedge only
    /// where `own` has one, a u-wedge of the same sign, a lens band still
    /// filtered), else `own`.
    Maaf6Wedge steady_wedge(const Maaf6Wedge &own, int x, int y) const {
        Maaf6Wedge steady = own;
        if (own.has_y && layer_.window_y_min.valid() && layer_.window_y_max.valid()) {
            const float lo = layer_.window_y_min(x, y), hi = layer_.window_y_max(x, y);
            if (lo >= 0 && std::isfinite(hi) && hi >= lo) {
                steady.y_min = std::min(own.y_min, double(lo));
                steady.y_max = std::max(own.y_max, double(hi));
            }
        }
        if (own.has_u && shared_.window_u_min.valid() && shared_.window_u_max.valid()) {
            const float lo = shared_.window_u_min(x, y), hi = shared_.window_u_max(x, y);
            Maaf6Wedge u = steady;
            u.u_min = std::min(own.u_min, double(lo));
            u.u_max = std::max(own.u_max, double(hi));
            const bool same_sign = (own.u_min * own.u_max > 0) == (u.u_min * u.u_max > 0);
            const bool lens_kept = own.has_y || maaf6_lens_band(u) > 0;
            if (std::isfinite(lo) && std::isfinite(hi) && hi >= lo && same_sign && lens_kept) steady = u;
        }
        return steady;
    }

    /// The wedge pixel (x, y) of wedge `own` is filtered with: the window's
    /// (steady_wedge()) where its filter carries the phases the sums were
    /// accumulated with (maaf6_pair_components() of `own`; the axis-aligned
    /// filter carries none), so that its widths hold still from frame to
    /// frame; else `own`.
    Maaf6Wedge filter_wedge(const Maaf6Wedge &own, int x, int y) const {
        const Maaf6Wedge steady = steady_wedge(own, x, y);
        if (steady.y_min == own.y_min && steady.y_max == own.y_max && steady.u_min == own.u_min &&
            steady.u_max == own.u_max)
            return own;
        const int pairs = pixel_pairs(shared_, params_, x, y);
        const double window_m = double(params_.max_radius_px) * double(shared_.pixel_size(x, y));
        const std::vector<Maaf6Component> filter =
            maaf6_filter_components(steady, pairs, params_.k, window_m);
        const std::vector<Maaf6Component> stored = maaf6_pair_components(own, pairs);
        for (std::size_t p = 1; p < filter.size(); ++p)
            if (filter[p].weight != 0 &&
                (filter[p].centre_y != stored[p].centre_y || filter[p].centre_u != stored[p].centre_u))
                return own;
        return steady;
    }

    /// The components of pixel (x, y) with their weights (the pair weights
    /// chosen), its frame and its windows; fills `envelope_px` with offsets.
    PixelFilter pixel_filter(const Maaf6Wedge &wedge, int x, int y, std::vector<double> &envelope_px) const {
        PixelFilter f;
        const double window_m = double(params_.max_radius_px) * double(shared_.pixel_size(x, y));
        f.pairs = maaf6_filter_components(wedge, pixel_pairs(shared_, params_, x, y), params_.k, window_m);
        // Where the offset pairs have weight 0 (the axis-aligned fallback) their kernels are 0:
        // only the central channel is gathered, with the same result.
        f.offsets_used = std::any_of(f.pairs.begin() + 1, f.pairs.end(),
                                     [](const Maaf6Component &c) { return c.weight != 0; });
        if (!f.offsets_used) f.pairs.resize(1);
        if (params_.pair_weights == Maaf6PairWeights::One && f.offsets_used)
            for (Maaf6Component &c : f.pairs) c.weight = 1.0;
        if (params_.pair_weights == Maaf6PairWeights::Light && f.offsets_used)
            for (Maaf6Component &c : f.pairs)
                c.weight *= maaf6_light_attenuation(c.centre_y, wedge.omega_y_max);
        if (params_.pair_weights == Maaf6PairWeights::Fitted && f.offsets_used) {
            // The partition is used, so the wedge is neither clipped by the x band nor
            // widened (pixel_pairs): its slope ratio is all the fit depends on.
            const double u_lo = std::min(std::fabs(wedge.u_min), std::fabs(wedge.u_max));
            const double u_hi = std::max(std::fabs(wedge.u_min), std::fabs(wedge.u_max));
            const MaafFittedWeights &table = wedge.has_y ? *fitted_y_ : *fitted_u_;
            const double ratio = wedge.has_y ? wedge.y_min / wedge.y_max : u_lo / u_hi;
            double mu[kMaafMaxPairs];
            table.weights(ratio, mu);
            for (std::size_t p = 1; p < f.pairs.size(); ++p) f.pairs[p].weight = mu[p - 1];
        }
        f.pixel_n = f.offsets_used ? used_n_ : 1;
        f.p = read3(shared_.position, x, y);
        f.n = normalize(read3(shared_.normal, x, y));
        maaf6_tangent_frame(f.n, light_.axis_u, light_.axis_v, f.t1, f.t2);
        f.std_m = f.pairs[0].sigma_x > 0 ? params_.k / f.pairs[0].sigma_x : 1e30;
        f.r = window_radius(shared_, params_, x, y, f.std_m);
        // The unoccluded light that multiplies the filtered ratio: with a lens wedge its samples
        // see whatever surface the lens ray hits (across a blurred silhouette, the surface behind),
        // so the pixel's own mean carries all of the defocus noise. It varies with u alone, so it
        // is filtered with the lens wedge's own axis-aligned band (never wider than the ratio's).
        const double lens_band = maaf6_lens_band(wedge);
        f.lens_std_m = lens_band > 0 ? params_.k / lens_band : 0.0;
        // With the partition: the axis-aligned filter alongside (MYRD14's, maaf6_pair_components(w, 1)),
        // and how much of the central envelope's mass the window keeps (kMinWindowMass).
        // It is computed as `--pairs 1` computes it, over its own window, so that it gives the same bits.
        if (f.offsets_used) f.axis_aligned = maaf6_pair_components(wedge, 1);
        f.axis_aligned_std_m =
            f.offsets_used && f.axis_aligned[0].sigma_x > 0 ? params_.k / f.axis_aligned[0].sigma_x : 1e30;
        f.axis_aligned_r = window_radius(shared_, params_, x, y, f.axis_aligned_std_m);
        f.x_kernel = Maaf6XKernel(f.pairs, params_.k);
        if (f.offsets_used) f.axis_aligned_x_kernel = Maaf6XKernel(f.axis_aligned, params_.k);
        f.mass_all = f.offsets_used
                         ? window_envelope(f.std_m / std::max(1e-12, double(shared_.pixel_size(x, y))), f.r,
                                           envelope_px)
                         : 0.0;
        return f;
    }

    /// Adds the accepted tap (tx, ty) of pixel (x, y) to its sums; k1, k2 hold
    /// 2N - 1 doubles each (the x kernels along t1 and t2).
    void add_tap(const PixelFilter &f, int x, int y, int tx, int ty, const std::vector<double> &envelope_px,
                 double *k1, double *k2, TapSums &s) const {
        // The tap minus the centre: h(x) = sum f(x', y, u) w(x - x', y, u) sees the
        // spectrum at (Omega_x, -Omega_y, -Omega_u), and our y, u axes point the way
        // that puts the wedge at positive slopes (README.md beside this file, "Filter").
        const Vec3 d = read3(shared_.position, tx, ty) - f.p;
        f.x_kernel(double(dot(d, f.t1)), k1);
        f.x_kernel(double(dot(d, f.t2)), k2);
        // Off the tangent plane (a step in depth, another surface of the same
        // normal), the central Gaussian of that distance: AAF's world distance.
        const double off_plane = double(dot(d, f.n)) / f.std_m;
        const double depth_weight = std::exp(-0.5 * off_plane * off_plane);
        // Per-pixel means, as AAF filters them: a pixel with more samples (the
        // focal-plane extra) is not weighted more than its neighbours.
        const float count = shared_.samples(tx, ty);
        const double per_sample = depth_weight / double(count);
        if (f.lens_std_m > 0) {
            const double lens_kernel = frame_gaussian(d, f.lens_std_m);
            s.unoccluded += lens_kernel * double(layer_.weights[0](tx, ty)) / double(count);
            s.unoccluded_den += lens_kernel;
        }
        if (f.offsets_used) {
            s.mass_kept +=
                envelope_px[std::size_t(std::abs(tx - x))] * envelope_px[std::size_t(std::abs(ty - y))];
            if (std::abs(tx - x) <= f.axis_aligned_r && std::abs(ty - y) <= f.axis_aligned_r) {
                double a1, a2;  // the steps of the gather below, for N = 1
                f.axis_aligned_x_kernel(double(dot(d, f.t1)), &a1);
                f.axis_aligned_x_kernel(double(dot(d, f.t2)), &a2);
                const double off = double(dot(d, f.n)) / f.axis_aligned_std_m;
                a1 *= std::exp(-0.5 * off * off) / double(count);
                const double kernel = a1 * a2;
                s.den1 += kernel * double(layer_.weights[0](tx, ty));
                for (int col = 0; col < 3; ++col)
                    s.num1[col] += kernel * double(layer_.sums[std::size_t(col)](tx, ty));
            }
        }
        for (int a = 0; a < f.pixel_n; ++a) k1[a] *= per_sample;
        for (int a = 0; a < f.pixel_n; ++a)
            for (int b = 0; b < f.pixel_n; ++b) {
                const int c = a * stored_n_ + b;  // the layout of the stored N
                const double kernel = k1[a] * k2[b];
                s.den += kernel * double(layer_.weights[std::size_t(c)](tx, ty));
                for (int col = 0; col < 3; ++col)
                    s.num[col] += kernel * double(layer_.sums[std::size_t(3 * c + col)](tx, ty));
            }
        const double central = k1[0] * k2[0];
        s.den0 += central * double(layer_.weights[0](tx, ty));
        for (int col = 0; col < 3; ++col)
            s.num0[col] += central * double(layer_.sums[std::size_t(col)](tx, ty));
    }

    /// The frame's taps as maaf6_row_sums() reads them: positions, unit normals (NaN where
    /// tap_accepted() never accepts the tap), 1 / samples, and the layer's planes (copied
    /// where a view is not a plain plane).
    void prepare_taps() {
        const int width = shared_.object_id.width, height = shared_.object_id.height;
        const std::size_t count = std::size_t(width) * std::size_t(height);
        tap_planes_.assign(7, std::vector<float>(count));
        parallel_for_rows(height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
                const Vec3 p = read3(shared_.position, x, y), n = read3(shared_.normal, x, y);
                const float len = length(n), samples = shared_.samples(x, y);
                const bool usable = shared_.object_id(x, y) != 0 && samples > 0 && len > 0;
                const float values[7] = {p.x,
                                         p.y,
                                         p.z,
                                         usable ? n.x / len : std::numeric_limits<float>::quiet_NaN(),
                                         n.y / len,
                                         n.z / len,
                                         usable ? 1.0f / samples : 0.0f};
                for (std::size_t k = 0; k < 7; ++k) tap_planes_[k][i] = values[k];
            }
        });
        const auto plane = [&](const ConstPlaneView &view) -> const float * {
            if (view.pixel_stride == 1 && view.row_stride == width) return view.data;
            layer_copies_.emplace_back(count);
            std::vector<float> &copy = layer_copies_.back();
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x)
                    copy[std::size_t(y) * std::size_t(width) + std::size_t(x)] = view(x, y);
            return copy.data();
        };
        for (const ConstPlaneView &v : layer_.sums) sum_planes_.push_back(plane(v));
        for (const ConstPlaneView &v : layer_.weights) weight_planes_.push_back(plane(v));
        detail::Maaf6Taps taps;
        taps.width = width;
        taps.height = height;
        taps.row_stride = width;
        taps.px = tap_planes_[0].data();
        taps.py = tap_planes_[1].data();
        taps.pz = tap_planes_[2].data();
        taps.nx = tap_planes_[3].data();
        taps.ny = tap_planes_[4].data();
        taps.nz = tap_planes_[5].data();
        taps.inv_samples = tap_planes_[6].data();
        taps.sums = sum_planes_.data();
        taps.weights = weight_planes_.data();
        taps.cos_threshold = float(cos_threshold_);
        taps_ = taps;
    }

    const Maaf6LayerInputs &layer_;
    const Maaf6SharedInputs &shared_;
    const LightPlane &light_;
    const Maaf6FilterParams &params_;
    const int stored_n_, used_n_;
    const double cos_threshold_;
    std::shared_ptr<const MaafFittedWeights> fitted_y_, fitted_u_;
    std::optional<detail::Maaf6Taps> taps_;  ///< set: the taps' sums by maaf6_row_sums()
    std::vector<std::vector<float>> tap_planes_;
    std::deque<std::vector<float>> layer_copies_;
    std::vector<const float *> sum_planes_, weight_planes_;
};

}  // namespace

void maaf6_filter_layer(const Maaf6LayerInputs &layer, const Maaf6SharedInputs &shared,
                        const LightPlane &light, const Maaf6FilterParams &params,
                        const std::array<PlaneView, 3> &out) {
    check_inputs(layer, shared, params);
    const LayerFilter filter(layer, shared, light, params);
    parallel_for_rows(shared.object_id.height, [&](int y) { filter.row(y, out); });
}

Maaf6PartitionCensus maaf6_partition_census(const Maaf6LayerInputs &layer, const Maaf6SharedInputs &shared,
                                            const Maaf6FilterParams &params) {
    check_inputs(layer, shared, params);
    const double cos_threshold = std::cos(double(params.normal_threshold_deg) * kPi / 180.0);
    std::vector<double> envelope_px;
    Maaf6PartitionCensus census;
    for (int y = 0; y < shared.object_id.height; ++y)
        for (int x = 0; x < shared.object_id.width; ++x) {
            Maaf6Wedge wedge;
            if (shared.object_id(x, y) == 0) {
                ++census.background;
            } else if (!pixel_wedge(layer, shared, params, x, y, wedge)) {
                ++census.no_wedge;
            } else {
                ++census.filtered;
                if (params.pairs_used > 1 && pixel_pairs(shared, params, x, y) == 1) {
                    ++census.band_widened;
                    continue;
                }
                const double window_m = double(params.max_radius_px) * double(shared.pixel_size(x, y));
                const Maaf6PartitionCheck c =
                    maaf6_partition_check(wedge, params.pairs_used, params.k, window_m);
                ++census.by_reasons[std::size_t(int(c.beyond_window) + 2 * int(c.band_clipped) +
                                                4 * int(c.focal_box))];
                if (params.pairs_used == 1 || !c.partition_used()) continue;
                // The window the filter gathers over, and how much of it the guides and the border keep.
                const std::vector<Maaf6Component> pairs =
                    maaf6_filter_components(wedge, params.pairs_used, params.k, window_m);
                const double std_m =
                    pairs[0].sigma_x > 0 ? params.k / pairs[0].sigma_x : 1e30;  // as the filter
                const int r = window_radius(shared, params, x, y, std_m);
                const double mass_all =
                    window_envelope(std_m / std::max(1e-12, double(shared.pixel_size(x, y))), r, envelope_px);
                const Vec3 n = normalize(read3(shared.normal, x, y));
                double mass_kept = 0;
                for (int ty = std::max(0, y - r); ty <= std::min(shared.object_id.height - 1, y + r); ++ty)
                    for (int tx = std::max(0, x - r); tx <= std::min(shared.object_id.width - 1, x + r); ++tx)
                        if (tap_accepted(shared, n, cos_threshold, tx, ty))
                            mass_kept += envelope_px[std::size_t(std::abs(tx - x))] *
                                         envelope_px[std::size_t(std::abs(ty - y))];
                census.window_cut += mass_kept < kMinWindowMass * mass_all;
            }
        }
    return census;
}

}  // namespace aaf
