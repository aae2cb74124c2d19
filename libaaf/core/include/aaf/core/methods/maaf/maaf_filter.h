#pragma once

#include <array>
#include <vector>

#include "aaf/core/contract/light_plane.h"
#include "aaf/core/contract/plane_view.h"
#include "aaf/core/methods/maaf/maaf_fitted_weights.h"

namespace aaf {

/// Per-pixel inputs of the MAAF filter, all of one size (aov_contract.h for
/// meanings and units).
struct MaafInputs {
    int pairs = 3;  ///< N the sums were accumulated with
    /// maaf_channel_count(pairs) planes each, in maaf_accumulation.h's layout:
    /// the samples' values and unoccluded values times the light-side functions.
    std::vector<ConstPlaneView> value_sums;
    std::vector<ConstPlaneView> unoccluded_sums;
    /// The wedge the sums were accumulated with (maaf_wedge.h); omega_x_max
    /// 0 where a pixel has none (it then keeps its unfiltered value).
    ConstPlaneView s_min;
    ConstPlaneView s_max;
    ConstPlaneView omega_x_max;
    /// Optional (invalid views: none): the slopes' extremes over a temporal
    /// window (roles::MaafWindowWedge). A pixel takes its widths from
    /// [min(s_min, window_s_min), max(s_max, window_s_max)] where that wedge
    /// partitions the same Omega_y^max as its own (the sums' phases follow
    /// it: MAAF Eq. 6), or where the central filter is used alone.
    ConstPlaneView window_s_min, window_s_max;
    std::array<ConstPlaneView, 3> position;
    std::array<ConstPlaneView, 3> normal;
    ConstPlaneView object_id;
    ConstPlaneView pixel_size;
    /// Optional: the samples the sums hold per pixel (the `spp` role); with
    /// it the filter follows them (MaafParams::band_spp).
    ConstPlaneView samples;
};

/// The offset pairs' weights mu_p (the central's is 1).
enum class MaafPairWeights {
    Eq10,    ///< MAAF Eq. 10 as printed: a Gaussian over the whole wedge
    One,     ///< mu_p = 1 (the paper's Table 2 accuracies match this reading)
    Light,   ///< MAAF Eq. 10 times the light's spectrum at C_y^p (its realised density, not in the paper)
    Fitted,  ///< MaafFittedWeights (MaafKernelForm::Maaf4D) with the light's density (not in the paper)
};

/// Parameters of the MAAF filter.
struct MaafParams {
    /// The light's Omega_y^max the sums were accumulated with, rad/m
    /// (maaf_light_omega_y_max(); header attribute aaf:maaf:omega_y_max).
    double omega_y_max_rad_per_m = 0;
    /// Filter pairs used: 0 = all of the sums' N; 1 = the central filter
    /// alone (AAF, MAAF Sec. 5: N = 1). Other values would need other C_y.
    int pairs_used = 0;
    /// Width scale of every component's x-side Gaussian: its Fourier-domain
    /// standard deviation is k sigma_x^p, so its primal one is 1 / (k sigma_x^p)
    /// metres. k = 1 is the paper's reading of sigma_x^p (MAAF Eq. 8-9: the
    /// box half-width as the Gaussian's std, which attenuates the band to
    /// exp(-1/2) at its edge). The default 3 is AAF's k (AAF Eq. 13, footnote
    /// 4: the std is 3 times the band, passing it almost flat), so with N = 1
    /// the filter is AAF's default one (k = 3, mu = 2 = MAAF's light band).
    double k = 3.0;
    /// Taps whose normal turns more than this are rejected (MAAF Sec. 6.2: 20); degrees.
    float normal_threshold_deg = 20.0f;
    /// Taps stop at 3 standard deviations of a component's x-side Gaussian,
    /// and never beyond this bound; pixels.
    int max_radius_px = 64;
    /// Two 1D passes per component pair (complex exponentials, AAF Sec. 6's
    /// separation); false: every tap of the square window (MAAF Eq. 21
    /// directly, through gather_modulated), slower, to measure the approximation.
    bool separable = true;
    /// The samples per pixel at which the bands are the render's (16: the
    /// tracer's first pass). A pixel with n > band_spp samples (MaafInputs::
    /// samples) has its light and pixel bands widened by sqrt(n / band_spp),
    /// as AAF's mu grows with the square root of the samples (AAF Sec. 5.2),
    /// and gets the central filter alone at the widened bands (the sums'
    /// phases belong to the render's bands): the filter narrows as samples are
    /// added and a converged render is left as it is. 0: the render's bands
    /// whatever the samples (the paper's fixed width, whose bias stays).
    double band_spp = 16;
    /// The offset pairs' mu_p. Fitted: per pixel from its slope ratio s_min / s_max, where the wedge
    /// keeps the light's band (a wedge the pixel band clips gets MAAF Eq. 10's).
    MaafPairWeights pair_weights = MaafPairWeights::Eq10;
    /// What the light's samples are drawn from along one axis (light_sample_density(); Light and
    /// Fitted only; half_width 0: a uniform light of half width 2 / Omega_y^max).
    SampleDensity light_density;

    /// Throws aaf::Error naming the first parameter out of range.
    void validate() const;
};

/// Multiple Axis-Aligned Filtering of soft-shadow visibility (Wu et al.
/// 2017, MAAF Eq. 21 in 4D): per pixel the components of its wedge (MAAF Eq. 6-10),
/// and for each pair of components (one per light axis) the channels'
/// x-side kernels g(du; 1/sigma_x^p) g(dv; 1/sigma_x^q) times 1, cos(C_x du)
/// or -sin(C_x du) per axis, du, dv being a tap's signed displacement from the
/// centre along the light's two tangent axes (world metres), summed with
/// weights mu_p sigma_x^p (2 mu_p for p >= 1: the pair of MAAF Eq. 12-13). The
/// result is that sum over the value sums divided by the same sum over the
/// unoccluded sums, so a fully lit region stays exactly lit. Taps on another
/// object or with a normal beyond the threshold are rejected. A pixel
/// without a wedge, or whose normalising sum is not positive, falls back to
/// the central filter alone, then to its unfiltered value; no NaN or Inf is
/// written. Pixels with more samples than MaafParams::band_spp get the
/// central filter at bands widened to their samples. Runs on the current oneTBB arena; thread-count
/// independent. Throws aaf::Error on mismatched sizes or bad parameters.
void maaf_filter(const MaafInputs &inputs, const LightPlane &light, const MaafParams &params,
                 PlaneView filtered_visibility);

}  // namespace aaf
