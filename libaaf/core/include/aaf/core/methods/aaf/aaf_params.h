#pragma once

#include <string>

#include "aaf/core/kernels/light_bandlimit.h"
#include "aaf/core/math/vec3.h"

namespace aaf {

/// How the spatially varying Gaussian of AAF Eq. 10-12 is evaluated.
enum class AafFilterMode {
    Separable,  ///< a vertical then a horizontal 1D pass (Sec. 6); exact where beta is locally constant
    Exact2D,    ///< the full 2D gather of AAF Eq. 10 over the square window; slower, for measuring Sec. 6's
                ///< approximation
};

/// How tap distances are measured in the light's plane (AAF Eq. 12).
enum class AafLightDistance {
    /// The tap is slid along the direction from the centre pixel to the
    /// light's centre onto the plane through the centre parallel to the light,
    /// then measured there: equal to AAF Eq. 12 for a receiver facing the light,
    /// but a tilted light no longer shrinks displacements towards it. The
    /// default: to first order, a receiver moved along the ray to the light
    /// keeps its shadow, and one moved along the light's normal shifts it by
    /// the ray's slope (libaaf/core/methods/aaf/README.md).
    AlongLightDirection,
    /// AAF Eq. 12 as printed: the orthogonal projection onto the light's plane.
    OrthogonalProjection,
    /// The orthogonal projection, except at receivers within ~6 degrees of
    /// perpendicular to the light's plane (|n . n_L| < kDegenerateProjectionCos),
    /// where it collapses their displacements to nothing (every tap of such a
    /// face would weigh 1, whatever beta) and the distance is measured along
    /// the direction to the light instead.
    Guarded,
};

/// Below this |cos| between a receiver's normal and the light's, AAF Eq. 12's
/// projection is treated as degenerate (AafLightDistance::Guarded) and the
/// projected pixel footprint (AafParams::projected_pixel) stops shrinking.
inline constexpr float kDegenerateProjectionCos = 0.1f;

/// The pixel footprint in the light plane's units: the receiver's footprint
/// `pixel_size_m` shrinks by |cos| of the angle between the receiver's and
/// the light's planes along one axis under AAF Eq. 12's projection; the
/// smaller axis bounds the band-limit (AAF Eq. 6). `receiver_normal` need not
/// be unit; a zero or non-finite one leaves the footprint as it is.
float projected_pixel_size_m(float pixel_size_m, Vec3 receiver_normal, Vec3 light_normal);

/// How a rectangular light's two axes enter the band-limit (light_bandlimit.h).
enum class AafLightAxes {
    /// Each light axis its own band-limit, so the filter is an anisotropic
    /// Gaussian in the light's plane (beta_u along axis_u, beta_v along axis_v)
    /// and the rate of AAF Eq. 15 a product of the two axes' factors: a long
    /// light blurs more along its long axis.
    PerAxis,
    /// The sharper axis's band-limit for both: an isotropic filter, narrower
    /// than either axis needs along the long one (the paper's square light
    /// cannot tell the two apart).
    Shortest,
};

const char *to_string(AafLightAxes axes);
/// Parses "per_axis" or "shortest"; throws aaf::Error otherwise.
AafLightAxes light_axes_from_string(const std::string &name);

/// Parameters of Axis-Aligned Filtering (Mehta et al. 2012). The defaults are
/// the paper's (Sec. 6: k = 3, alpha = 1, mu = 2).
struct AafParams {
    /// Scale of the critical filter's frequency width, Omega_x^f = mu Omega_x0^f
    /// (Sec. 5.2): beta shrinks as 1/mu, the sampling rate grows with mu.
    float mu = 2.0f;
    /// Consistency (Sec. 5.2): each pixel's mu is raised to the value whose
    /// sampling rate (AAF Eq. 15/21) equals the samples the pixel actually took,
    /// so the filter narrows as samples are added and the result converges to
    /// the reference; `mu` is then the floor. This is the default whenever
    /// the spp AOV is given (AafInputs::spp valid); `mu_from_spp` makes the
    /// spp AOV required, `fixed_mu` ignores it (one mu everywhere, the
    /// filter of AAF Eq. 13 as printed).
    bool mu_from_spp = false;
    bool fixed_mu = false;
    /// Which sigma gives the light's band-limit Omega_L = 1/sigma and width
    /// 2 sigma in AAF Eq. 8, 13 and 15 (light_bandlimit.h); the sampling plan
    /// uses the same. The default is the paper's reading: with tap distances
    /// measured along the ray (light_distance), the truncated profile's wider
    /// spectrum (EquivalentWidth, Spectrum) makes the filter too narrow on the
    /// study scenes (libaaf/core/methods/aaf/README.md).
    LightBandlimit light_bandlimit = LightBandlimit::Sigma;
    AafLightAxes light_axes = AafLightAxes::PerAxis;
    /// Baseline "non-adaptive filter" of AAF Fig. 6 (NAF): when > 0, every pixel
    /// AAF would filter uses this beta (world metres) instead of AAF Eq. 13, with
    /// the same taps, rejection and cut-off. 0 = AAF proper.
    float fixed_beta_m = 0.0f;
    /// Gaussian energy spread, beta = 1 / (k Omega_x^f) (AAF Eq. 13, footnote 4).
    float k = 3.0f;
    /// Occluder bandlimit relative to the pixel bandlimit, in (0, 1] (AAF Eq. 5).
    float alpha = 1.0f;
    /// Taps whose normal turns by more than this from the centre's are rejected
    /// (Sec. 6 "check on normal variation"); degrees.
    float normal_threshold_deg = 25.0f;
    /// Unoccluded pixels borrow occluder distances from occluded pixels of the
    /// same object within this radius (Sec. 6: 5 pixels); pixels.
    int fill_radius_px = 5;
    /// Taps stop at 3 beta (weights below exp(-4.5) = 1.1% are dropped), i.e. at
    /// ceil(3 beta / pixel_size) pixels, and never beyond this bound; pixels.
    int max_radius_px = 64;
    AafFilterMode mode = AafFilterMode::Separable;
    /// Windows cut by the image edge are cut on the other side too (centred,
    /// unbiased on gradients); false: cut on the edge side only, the kernel
    /// one-sided (the plain reading of Sec. 6).
    bool symmetric_borders = true;
    AafLightDistance light_distance = AafLightDistance::AlongLightDirection;
    /// The pixel band-limit Omega_pix = 1/d of AAF Sec. 4.1 (Eq. 6, 15) with d
    /// measured in the light plane's units, like the tap distances of AAF Eq. 12
    /// (projected_pixel_size_m()); false (the default): the receiver's own
    /// footprint (the paper's reading, exact for a receiver parallel to the light).
    bool projected_pixel = false;

    /// Throws aaf::Error naming the first parameter out of range.
    void validate() const;
};

}  // namespace aaf
