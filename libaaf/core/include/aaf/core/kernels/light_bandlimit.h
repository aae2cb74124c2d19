#pragma once

#include <string>

#include "aaf/core/contract/light_plane.h"

namespace aaf {

/// Which sigma stands for the light in AAF's band-limit Omega_L^max = 1/sigma
/// (Sec. 4.1) and effective width 2 sigma (AAF Eq. 15). The paper assumes an
/// untruncated Gaussian; the lights here are truncated at the rectangle's
/// edges (1 sigma for a square by default, light_plane.h), which spreads the
/// spectrum: Omega_L = 1/sigma understates the band-limit and over-blurs.
enum class LightBandlimit {
    /// The profile's sigma itself (the paper's Sec. 4.1 reading).
    Sigma,
    /// The sigma of the Gaussian whose spectrum falls to exp(-1/2) (its value
    /// at Omega = 1/sigma) at the same frequency as the truncated profile's.
    Spectrum,
    /// The sigma of the Gaussian with the profile's peak-normalised area
    /// (equivalent width): sigma erf(h / (sigma sqrt 2)) per axis of half-extent h.
    EquivalentWidth,
};

const char *to_string(LightBandlimit rule);
/// Parses "sigma", "spectrum" or "equivalent_width"; throws aaf::Error otherwise.
LightBandlimit light_bandlimit_from_string(const std::string &name);

/// The sigma (metres) whose 1/sigma is the light's band-limit Omega_L^max
/// under `rule`: per axis of the rectangle (half-extent h = width/2, height/2,
/// profile Gaussian of `sigma_m` or uniform), the larger band-limit of the
/// two wins (the filter is isotropic in the light's plane, so the sharper
/// axis bounds it). For an untruncated Gaussian (h >= 8 sigma) every rule
/// gives sigma_m. Throws aaf::Error unless the light validates.
float light_bandlimit_sigma_m(const LightPlane &light, LightBandlimit rule);

/// The band-limit sigma of each of the light's axes on its own (metres):
/// u along axis_u (half-extent width/2), v along axis_v (height/2). AAF's
/// analysis is separable in the light's two axes (the 4D spectrum of Sec. 4
/// is a product of two 2D wedges), so a rectangle gets one band-limit per
/// axis; light_bandlimit_sigma_m() is the smaller of the two.
struct LightBandlimitAxes {
    float u_m = 0;
    float v_m = 0;
};
LightBandlimitAxes light_bandlimit_axes_m(const LightPlane &light, LightBandlimit rule);

}  // namespace aaf
