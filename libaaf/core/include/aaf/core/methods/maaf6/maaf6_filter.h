#pragma once

#include <array>
#include <vector>

#include "aaf/core/contract/light_plane.h"
#include "aaf/core/contract/plane_view.h"
#include "aaf/core/methods/maaf/maaf_fitted_weights.h"

namespace aaf {

/// One layer (direct or indirect) of a maaf6 render (libaaf/AOV_CONTRACT.md,
/// "The maaf6.* layer"), with the pixel data every layer shares.
struct Maaf6LayerInputs {
    std::vector<ConstPlaneView> sums;     ///< 3 (2N-1)^2 planes: channel c's R, G, B at 3c .. 3c+2
    std::vector<ConstPlaneView> weights;  ///< (2N-1)^2 planes
    ConstPlaneView y_min, y_max;          ///< the layer's y slopes; -1 in both = no y-wedge
    /// Optional (invalid views: none): the y slopes' extremes over a temporal
    /// window (roles::Maaf6WindowWedge), for the widths the phases leave free.
    ConstPlaneView window_y_min, window_y_max;
    double omega_y_max = 0;   ///< the layer's Omega_y^max (light: rad/m; indirect: rad)
    SampleDensity y_density;  ///< what y is drawn from (Maaf6PairWeights::Fitted only)
};

struct Maaf6SharedInputs {
    ConstPlaneView u_min, u_max;  ///< defocus slopes 1 - z/F
    /// Optional, as Maaf6LayerInputs::window_y_min: the u slopes' extremes over the window.
    ConstPlaneView window_u_min, window_u_max;
    ConstPlaneView omega_x;  ///< pixel band-limit, rad/m
    std::array<ConstPlaneView, 3> position, normal;
    ConstPlaneView object_id;  ///< 0 = background (no primary hit)
    ConstPlaneView pixel_size;
    ConstPlaneView samples;      ///< path samples per pixel (maaf6.spp)
    double omega_u_max = 0;      ///< 0 = pinhole (no u-wedge)
    SampleDensity lens_density;  ///< what u is drawn from (Maaf6PairWeights::Fitted only)
};

/// The offset pairs' weights mu_p.
enum class Maaf6PairWeights {
    Eq10,    ///< MAAF Eq. 10, as the paper
    One,     ///< mu_p = 1 (the paper's Table 2 accuracies match this reading)
    Light,   ///< MAAF Eq. 10 times maaf6_light_attenuation() at C_y^p (a Gaussian light model; not in the
             ///< paper)
    Fitted,  ///< MaafFittedWeights: fitted to the sampling density's spectrum along the wedge (not in the
             ///< paper)
};

struct Maaf6FilterParams {
    int stored_pairs = 3;             ///< N of the sums
    int pairs_used = 3;               ///< N of the filter: stored_pairs, or 1 (the central filter alone: AAF)
    double k = 1;                     ///< width scale, as `aaf filter maaf --k` (1: the paper's reading)
    float normal_threshold_deg = 20;  ///< MAAF Sec. 6.2: taps whose normal turns more are rejected
    int max_radius_px = 12;
    /// The offset pairs' mu_p. Fitted: per pixel from the y-wedge's slope ratio
    /// with the layer's y_density, or, without a y-wedge, the u-wedge's with
    /// the lens_density (the u phases of a pixel with both are not in the fit).
    Maaf6PairWeights pair_weights = Maaf6PairWeights::Fitted;
    /// The samples per pixel at which the y and u bands are MAAF Sec. 3's: a
    /// pixel with n > band_spp samples has them widened by sqrt(n / band_spp),
    /// AAF Sec. 5.2's consistency (mu grows as the square root of the
    /// samples), so its filter narrows as samples are added and the filtered
    /// image converges to the reference. Such a pixel gets the axis-aligned
    /// filter (N = 1) at its widened bands: the stored phases belong to the
    /// render's bands. 16 (the default): the first pass's samples; the maaf6
    /// method passes 128 for the indirect layer (`--indirect-band-spp`). 0: the bands
    /// whatever the samples, as the paper has them, whose bias no sample count
    /// removes (libaaf/core/methods/maaf6/README.md, "Consistency").
    double band_spp = 16;
    /// true: each tap for a vector of centres at once, in float with polynomial exp and sin/cos
    /// (the same bits on every instruction set); false: one centre at a time in double with the
    /// C library's, the reference the tests compare with. The same filter otherwise.
    bool vectorised = true;
};

/// Filters one layer (MAAF Eq. 21-22 with the 6D product of MAAF Sec. 6.2):
/// for every pixel i, with t1, t2 its maaf6_tangent_frame() and components
/// maaf6_filter_components() of its wedge (window: max_radius times its pixel
/// size; the axis-aligned filter where the partition cannot be realised), out = sum_j g_j sum_ab K_a(d1)
/// K_b(d2) sums_j[ab] / (the same with weights_j[ab]), d_k = (P_j - P_i) . t_k (the tap minus the centre: see
/// methods/maaf6/README.md for the orientation), g_j = exp(-d_n^2 / (2 s^2)) / samples_j with d_n = (P_i -
/// P_j) . n the distance off the tangent plane and s the central component's primal std (so taps are
/// per-pixel means, as AAF filters, and a step in depth counts as AAF's world distance does), times the
/// pixel's own mean weight weights_i[c0c0] / samples_i (1 with unit weights; the mean unoccluded luminance
/// for direct light: AAF's r(x) V(x) factoring), over the window of radius min(max_radius, ceil(3 k /
/// sigma_x^0 / pixel size)), taps on the background or beyond the normal threshold rejected. A constant
/// radiance stays exactly constant. Where the denominator is below a tenth of the central term's alone, the
/// central term alone is used (AAF's filter), then the pixel's own mean; negative results are clamped to 0;
/// the background keeps its mean, and so does a pixel without a y-wedge whose u-wedge is absent (pinhole),
/// the focal-plane box (MAAF Sec. 6.2 gives it more samples instead: its pixel band is the pixel itself) or
/// clipped by the pixel band (Omega_u^max >= min |s_u| Omega_x^max: a circle of confusion of about a pixel,
/// whose filter would only blur). No NaN or Inf leaves it (inputs finite). Where the partition is used but
/// the guides (another normal, no hit) or the image's border take away more than 20% of the central
/// envelope's mass from the window, the pixel gets the axis-aligned filter (`--pairs 1`'s bits): the pairs'
/// cos and sin kernels cancel only over a whole window, and over a cut one they bias the pixel (room:
/// indirect light at 128 spp 28% above N = 1 without this rule, 5% with it). With a filtered lens wedge
/// (maaf6_lens_band() > 0) the unoccluded light that multiplies the filtered ratio is the Gaussian mean of
/// the taps' own with the lens band, not the pixel's own mean: its samples see whatever surface the lens ray
/// hits, so the own mean would carry the defocus noise through.
/// Writes `out` (3 planes). Throws aaf::Error on mismatched sizes.
void maaf6_filter_layer(const Maaf6LayerInputs &layer, const Maaf6SharedInputs &shared,
                        const LightPlane &light, const Maaf6FilterParams &params,
                        const std::array<PlaneView, 3> &out);

/// Where maaf6_filter_layer() uses the partition, and why not elsewhere
/// (maaf6_partition_check() of each pixel's wedge, window and k as the filter has them).
struct Maaf6PartitionCensus {
    long background = 0;  ///< no primary hit: the pixel keeps its mean
    long no_wedge = 0;    ///< a hit without a wedge to filter along: keeps its mean
    long filtered = 0;    ///< the rest: filtered by the partition or the central filter
    /// of the filtered pixels (N > 1), those whose bands band_spp widens: they get the axis-aligned
    /// filter at the widened band (the stored phases belong to the render's bands)
    long band_widened = 0;
    /// the other filtered pixels by the reasons that hold, index beyond_window + 2 band_clipped +
    /// 4 focal_box (index 0: the partition is used)
    std::array<long, 8> by_reasons{};
    /// of by_reasons[0]: pixels whose window the guides (other normals, no hit) or the image's border
    /// cut by more than 20% of the central envelope's mass, which get the axis-aligned filter instead
    long window_cut = 0;
};

/// Counts maaf6_filter_layer()'s choice per pixel for `layer`. Throws as it does.
Maaf6PartitionCensus maaf6_partition_census(const Maaf6LayerInputs &layer, const Maaf6SharedInputs &shared,
                                            const Maaf6FilterParams &params);

}  // namespace aaf
