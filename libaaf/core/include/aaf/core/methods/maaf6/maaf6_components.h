#pragma once

#include <array>
#include <vector>

#include "aaf/core/math/vec3.h"

namespace aaf {

/// MAAF for combined effects (Wu et al. 2017, MAAF Sec. 6.2): one pixel's 3D
/// wedge in flatland, (x, y, u) per image axis, with x the receiver's
/// displacement, y the light (direct) or the bounce direction (indirect) and
/// u the point on the lens. The 6D filter is the product of the two 3D
/// subspaces (x1, y1, u1) and (x2, y2, u2), as the 4D one of MAAF Fig. 7.
///
/// Units. x and u are metres (x: world displacement of the receiver along
/// one tangent axis; u: lens point along the same axis, metres from the lens
/// centre). y is metres on the light for direct light and, for indirect
/// light, the bounce direction on the unit plane above the receiver
/// (tan theta along the axis, unitless, as AAF for indirect light).
/// Frequencies are radians per unit of their coordinate.
struct Maaf6Wedge {
    /// y-wedge slopes (MAAF Sec. 3): direct s = d1/d2 - 1 (unitless); indirect
    /// s = z, the reflector distance in metres. has_y false: no y-wedge (an
    /// unoccluded pixel, a bounce that left the scene).
    bool has_y = false;
    double y_min = 0, y_max = 0;
    /// u-wedge slopes: s_u = 1 - z/F (z the receiver's depth, F the focus
    /// distance), the world-unit form of MAAF Sec. 3's V(F/z - 1)/S (derived in
    /// methods/maaf6/README.md; it is that slope times the pixel footprint z/F S/V, with
    /// the sign of the lens axis). May have either sign; u_min u_max < 0 is the
    /// focal-plane box (MAAF Sec. 6.2). has_u false: a pinhole camera.
    bool has_u = false;
    double u_min = 0, u_max = 0;
    double omega_y_max = 0;  ///< band-limit along y: 2 / sigma of the light, or 2.8 (indirect)
    double omega_u_max = 0;  ///< band-limit along u: 4 / A for an aperture of radius A (MAAF Sec. 3, L = A)
    double omega_x_max = 0;  ///< pixel band-limit along x, rad/m (> 0)
};

/// One pair p >= 0 of 3D components (MAAF Eq. 22): Fourier centres and
/// half-widths along x, y, u and the weight mu_p.
struct Maaf6Component {
    int index = 0;
    double centre_x = 0, sigma_x = 0;  ///< rad/m (MAAF Eq. 7-8)
    double centre_y = 0, sigma_y = 0;  ///< rad per y unit (MAAF Eq. 6, 8)
    double centre_u = 0, sigma_u = 0;  ///< rad/m on the lens (MAAF Eq. 24, see maaf6_pair_components)
    double weight = 0;                 ///< mu_p (MAAF Eq. 10)
};

/// Pairs p = 0 .. N-1 covering `wedge` (N = `pairs`, 1 .. kMaafMaxPairs).
///
/// MAAF Sec. 6.2's partition: the x band is first lowered to what every
/// wedge allows (the "simple optimization": the y-wedge's Omega_y^max / y_min
/// and, when both u slopes have one sign, Omega_u^max / min |s_u|); the y axis
/// is split into 2N - 1 slices (MAAF Eq. 6-10, maaf_components()); each
/// component's x range [a, b] is mapped through the u-wedge to the u range
/// {s a .. s b : s in [u_min, u_max]}, clipped to +-Omega_u^max, whose centre
/// and half-width are C_u^p and sigma_u^p. This is Fig. 11(c) as the text
/// describes it; MAAF Eq. 24 as printed mixes u-slope ratios with Omega_y^max and
/// is not dimensionally consistent, so it is not used literally.
///
/// Without a y-wedge the u-wedge is partitioned instead (C_y = 0): with
/// one-signed u slopes as a 2D MAAF over (x, u); in the focal-plane box
/// (mixed signs) or with neither wedge, only the central component at the
/// pixel band remains (the others get weight 0). Always finite.
std::vector<Maaf6Component> maaf6_pair_components(const Maaf6Wedge &wedge, int pairs);

/// The components the 6D filter uses at one pixel: maaf6_pair_components(wedge,
/// pairs) where the 3D partition can be realised there, otherwise the central
/// axis-aligned filter at N = 1 (maaf6_pair_components(wedge, 1) as component
/// 0, the N - 1 offset pairs kept with weight 0, so the stored layout stays).
/// The partition cannot be realised, and its offset pairs would only bias:
///  - when the central component's primal reach 3 k / sigma_x^0 exceeds the
///    filter window `window_m` (max_radius pixels times the pixel size): inside
///    the window cos(C_x^p dx) is about 1 and sin about 0, so each pair stops
///    being a sheared filter and becomes a reweighting of the pixel's own samples by
///    1 + 2 mu_p cos(C_y^p y), which favours y near 0 (for indirect light the
///    directions about the normal: floors came out too dark, ceilings too bright);
///  - when the wedge's x extent is the x band itself, not its y (or u, without
///    a y-wedge) band: Omega^max / s_min >= the x band (MAAF Sec. 6.2's "simple
///    optimization" clips the wedge). The central component is then 2N - 1 times
///    narrower than the pixel band and the Gaussian pairs tile the rest
///    unevenly: in-focus and hard-shadow edges, whose slopes lie below the
///    5x5-averaged s_min, leak and ring over the whole window;
///  - in the focal-plane box (has_u with u slopes of both signs, MAAF Sec. 6.2:
///    the double wedge degenerates to a box and the pixel gets extra samples
///    instead): every component's u range then contains 0, so the u-wedge has
///    nothing to pack, and the pairs only over-sharpen the y-wedge (room,
///    320x240, 16 spp: the direct layer's RMSE on the focal-plane pixels that
///    used the partition was 0.061, against 0.011 with the central filter;
///    centring their u phases on 0 changed nothing, 0.061).
/// k: the filter's width scale (Maaf6FilterParams::k). Throws as maaf6_pair_components().
std::vector<Maaf6Component> maaf6_filter_components(const Maaf6Wedge &wedge, int pairs, double k,
                                                    double window_m);

/// Which of maaf6_filter_components()'s reasons hold at one pixel (several can):
/// beyond_window (a), band_clipped (b), focal_box (c), in the order listed there.
/// The partition is used where none holds. For N = 1 none is reported (there is
/// nothing to fall back from). Throws as maaf6_pair_components().
struct Maaf6PartitionCheck {
    bool beyond_window = false;
    bool band_clipped = false;
    bool focal_box = false;
    bool partition_used() const { return !beyond_window && !band_clipped && !focal_box; }
};
Maaf6PartitionCheck maaf6_partition_check(const Maaf6Wedge &wedge, int pairs, double k, double window_m);

/// The x band of the pixel's lens wedge alone, Omega_u^max / min |s_u| (MAAF
/// Sec. 3 with L = A): the band of what varies with the lens point only, such
/// as the unoccluded direct light, whose samples hit the surfaces the lens
/// ray sees (another surface across a blurred silhouette). 0 where that wedge
/// is absent (pinhole), the focal-plane box (u slopes of both signs), or
/// clipped by the pixel band (a circle of confusion of about a pixel or less:
/// the samples then vary over less than the filter, and the pixel's own mean is
/// the estimate). Throws as maaf6_pair_components().
double maaf6_lens_band(const Maaf6Wedge &wedge);

/// The y band's attenuation at a pair's y centre, G(C_y^p; Omega_y^max / 2) =
/// exp(-(sigma C_y^p)^2 / 2) for Omega_y^max = 2 / sigma: the spectrum of the
/// Gaussian light (or lobe) model whose band-limit MAAF Sec. 3 takes as
/// Omega_y^max. A pair whose y-envelope is the sampling density itself passes
/// the wedge near (C_x^p, C_y^p) with gain mu_p, while the y integral attenuates
/// it by the light's spectrum there; MAAF Eq. 10's G(C_y^p; Omega_y^max) is twice as
/// wide (0.73 instead of 0.28 at C_y = 0.8 Omega_y^max, N = 3), so the outer pairs
/// over-sharpen. Optional (Maaf6FilterParams::light_weights): not in the paper.
/// 1 for C_y = 0. Throws aaf::Error unless omega_y_max > 0.
double maaf6_light_attenuation(double centre_y, double omega_y_max);

/// Channels per layer and per colour: (2N - 1)^2, channel a (2N - 1) + b
/// being function a of subspace 1 times function b of subspace 2; function
/// 0 is 1, 2p - 1 is cos(C_y^p y + C_u^p u), 2p is sin(...) (MAAF Eq. 23).
int maaf6_channel_count(int pairs);

/// One pixel's sample side (MAAF Eq. 23 by Monte Carlo). The Gaussian
/// envelopes g(y; 1/sigma_y) g(u; 1/sigma_u) are the sampling densities
/// themselves (light profile, uniform aperture, cosine lobe), as the 4D
/// MaafLightSide does for y; the phases carry the components' centres.
class Maaf6SampleSide {
  public:
    explicit Maaf6SampleSide(const std::vector<Maaf6Component> &pairs);
    int pairs() const { return pairs_; }
    int channels() const { return maaf6_channel_count(pairs_); }
    /// The 2N - 1 functions at (y, u) of one subspace, into phi.
    void evaluate(double y, double u, double *phi) const;
    /// Adds one sample: for every channel c = a (2N-1) + b,
    /// rgb_sums[3 c + k] += value[k] phi_a(y1, u1) phi_b(y2, u2) and
    /// weight_sums[c] += weight phi_a phi_b, whose filtered sums normalise the
    /// result (weight 1 for a plain average; for direct light the sample's
    /// unoccluded luminance, so the filter divides out the shading as AAF's
    /// r(x) V(x) factoring does).
    void accumulate(double y1, double u1, double y2, double u2, const float value[3], double weight,
                    double *rgb_sums, double *weight_sums) const;

  private:
    int pairs_ = 1;
    std::array<double, 8> centre_y_{};
    std::array<double, 8> centre_u_{};
};

/// The x-side kernel of one subspace at displacement dx_m = x - x' (MAAF
/// MAAF Eq. 21-22): into kernel[0 .. 2N-2], function 0: g(dx; k/sigma_x^0);
/// 2p - 1: 2 mu_p (cos(C_x^p dx) - e_p) g(dx; k/sigma_x^p); 2p: -2 mu_p sin(C_x^p dx)
/// g(...), so that sum_a kernel[a] phi_a = MAAF Eq. 22's primal filter per
/// subspace (cos(A + B) = cos A cos B - sin A sin B, MAAF Eq. 13), less
/// e_p = exp(-(k C_x^p / sigma_x^p)^2 / 2), the DC of cos(C_x^p dx) g: each pair's
/// x kernel integrates to 0 (as a Morlet wavelet's correction), so it passes
/// nothing at Omega_x = 0. Without it the Gaussian's tail at Omega_x = 0 (e_p is
/// 0.6 for C_x = sigma_x) weights a pixel's own y integral by cos(C_y^p y), a
/// bias no sample count removes; with it the mean over the window is the
/// central filter's, an unweighted integral over y and u.
/// g(t; s) = exp(-t^2 / (2 s^2)); k scales every Fourier std (as `aaf filter maaf --k`).
void maaf6_x_kernel(const std::vector<Maaf6Component> &pairs, double k, double dx_m, double *kernel);

/// maaf6_x_kernel() for one pixel's components, evaluated at many
/// displacements: what does not depend on the displacement (each pair's DC
/// correction e_p) is computed once. The same bits as maaf6_x_kernel().
class Maaf6XKernel {
  public:
    Maaf6XKernel() = default;
    Maaf6XKernel(const std::vector<Maaf6Component> &pairs, double k);
    void operator()(double dx_m, double *kernel) const;

  private:
    struct Pair {
        double sigma_x, centre_x, weight, dc;
    };
    std::vector<Pair> pairs_;
    double k_ = 1;
};

}  // namespace aaf

namespace aaf {

/// The pixel's two tangent axes t1, t2 (unit, t1 x t2 = n): t1 is the light's
/// axis_u projected on the tangent plane of unit normal n (axis_v's when
/// axis_u is within 25 degrees of n), t2 = n x t1. x displacements, light
/// points, lens points and bounce directions are all projected on these, so
/// each 3D subspace has one axis (MAAF Sec. 6.2). The tracer and the filter
/// build it alike from the same normal.
void maaf6_tangent_frame(Vec3 n, Vec3 light_axis_u, Vec3 light_axis_v, Vec3 &t1, Vec3 &t2);

}  // namespace aaf
