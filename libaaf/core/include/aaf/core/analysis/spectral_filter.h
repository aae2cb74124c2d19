#pragma once

#include <vector>

#include "aaf/core/analysis/wedge_spectrum.h"

namespace aaf {

/// The profile of every component of a SpectralFilter: boxes (MAAF Sec. 5,
/// Table 1) or Gaussians G(Omega; sigma) = exp(-Omega^2 / (2 sigma^2)) with
/// peak 1 (MAAF Eq. 2, 4, 9; Table 2), so that a filter is compared with T = 1.
enum class SpectralShape { Box, Gaussian };

/// One axis-aligned (or sheared) component of a Fourier-domain filter, in the
/// (Omega_x, Omega_y) plane of DoubleWedge:
///   weight * P((Omega_x - C_x - shear (Omega_y - C_y)) / width_x) * P((Omega_y - C_y) / width_y)
/// with P(u) = [|u| <= 1] for boxes and exp(-u^2/2) for Gaussians.
struct SpectralComponent {
    double weight = 1;    ///< mu_p of MAAF Eq. 10 (1 for AAF, FSF and unweighted boxes)
    double center_x = 0;  ///< C_x, radians per metre (MAAF Eq. 7)
    double center_y = 0;  ///< C_y, radians per metre (MAAF Eq. 6)
    double width_x = 1;   ///< box half-width or Gaussian sigma along Omega_x (MAAF Eq. 8), > 0
    double width_y = 1;   ///< box half-width or Gaussian sigma along Omega_y (MAAF Eq. 8), > 0
    double shear = 0;     ///< Omega_x offset per unit Omega_y (FSF: 1/s_avg, MAAF Eq. 4); 0 = axis-aligned
};

/// A Fourier-domain filter W(Omega_x, Omega_y): the sum of its components.
struct SpectralFilter {
    SpectralShape shape = SpectralShape::Box;
    std::vector<SpectralComponent> components;

    /// W at (omega_x, omega_y).
    double value(double omega_x, double omega_y) const;
    /// The integral of W over the whole plane, in closed form: sum of
    /// weight * 4 width_x width_y (boxes) or weight * 2 pi width_x width_y
    /// (Gaussians); a shear does not change the area.
    double integral() const;
};

/// P(u) of SpectralComponent: 1 inside |u| <= 1 for boxes, exp(-u^2/2) for Gaussians.
double spectral_profile(SpectralShape shape, double u);

/// The axis-aligned filter of AAF (MAAF Eq. 2): centred at the origin,
/// width Omega_y^max / s_min along Omega_x and Omega_y^max along Omega_y. As a
/// box it is the smallest axis-aligned box holding T.
SpectralFilter aaf_spectral_filter(const DoubleWedge &wedge, SpectralShape shape);

/// The sheared filter of FSF (MAAF Eq. 4): centred on Omega_x = Omega_y / s_avg
/// (s_avg the harmonic mean of s_min and s_max), width Omega_y^max along
/// Omega_y. As a box it is the tight parallelogram of MAAF Sec. 5, half-width
/// Omega_y^max (1/s_min - 1/s_max) / 2 along Omega_x; as a Gaussian its sigma
/// along Omega_x is MAAF Eq. 4's Omega_y^max (1/s_min - 1/s_max), the full width of
/// that parallelogram (MAAF Eq. 4 as printed; AAF's and MAAF's sigmas equal their
/// boxes' half-widths).
SpectralFilter fsf_spectral_filter(const DoubleWedge &wedge, SpectralShape shape);

/// The 2N - 1 components of MAAF (MAAF Eq. 9) for `pairs` = N >= 1, placed by
/// MAAF Eq. 6-8 (maaf_components.h); Gaussians weighted by mu_p (MAAF Eq. 10) unless
/// `mu_weights` is false (then all 1, to see what MAAF Eq. 10 costs in accuracy),
/// boxes always unweighted as in Table 1. N = 1 is AAF's filter.
SpectralFilter maaf_spectral_filter(const DoubleWedge &wedge, int pairs, SpectralShape shape,
                                    bool mu_weights = true);

}  // namespace aaf
