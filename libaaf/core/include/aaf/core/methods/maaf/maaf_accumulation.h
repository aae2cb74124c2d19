#pragma once

#include <array>
#include <string>

namespace aaf {

/// Largest N (filter pairs per 2D subspace) the accumulation supports.
inline constexpr int kMaafMaxPairs = 8;

/// Light-side functions per light axis, 2N - 1: function 0 is the central
/// component's, 2p - 1 its cosine and 2p its sine for p = 1 .. N-1 (MAAF
/// MAAF Eq. 20, the primal pair of MAAF Eq. 13).
inline int maaf_functions_per_axis(int pairs) {
    return 2 * pairs - 1;
}
/// Channels per pixel, (2N - 1)^2: channel a (2N - 1) + b holds light-side
/// function a of the first light axis times function b of the second (the 4D
/// filter as the product of the two 2D subspaces, MAAF Sec. 6.1, Fig. 7).
inline int maaf_channel_count(int pairs) {
    return maaf_functions_per_axis(pairs) * maaf_functions_per_axis(pairs);
}
/// Short name of light-side function `function`: "c0", then "c1", "s1", "c2", "s2", ...
std::string maaf_function_name(int function);
/// Name of channel `channel` within a layer: function names of axis 1 and axis 2, e.g. "c1s2".
std::string maaf_channel_suffix(int pairs, int channel);

/// One pixel's light-side functions (MAAF Eq. 20 and 23, for soft shadows):
/// per light axis, 1, cos(C_y^p y) and sin(C_y^p y) for p = 1 .. N-1, with y
/// the sample's coordinate on the light along that axis (metres from the
/// light's centre) and C_y^p in radians per metre.
///
/// The Gaussian envelope g(y; 1/sigma_y) of MAAF Eq. 20 is the same for every
/// component (MAAF Eq. 8: sigma_y^p does not depend on p), and is taken to be the
/// light's own emission profile: the renderer samples y from the light (as
/// for AAF), so a sample's `value` already carries it. With N = 1 the sums
/// are the renderer's plain light-weighted sums, i.e. AAF's input.
class MaafLightSide {
  public:
    MaafLightSide() = default;
    /// N = `pairs` (1 .. kMaafMaxPairs) with C_y^p = omega 2p / (2N - 1) (MAAF
    /// MAAF Eq. 6), omega being the pixel's partitioned Omega_y^max in rad/m
    /// (maaf_partitioned_omega_y_max(); the light's Omega_y^max where a pixel
    /// has no wedge). Throws aaf::Error for pairs out of range or a negative
    /// or non-finite omega.
    MaafLightSide(int pairs, double omega_y_max_rad_per_m);

    int pairs() const { return pairs_; }
    int channels() const { return maaf_channel_count(pairs_); }

    /// The 2N - 1 functions at light coordinate y_m, into phi[0 .. 2N-2].
    void evaluate(double y_m, double *phi) const;

    /// Adds one sample to the pixel's sums (MAAF Eq. 20, 23 by Monte Carlo):
    /// value_sums[a (2N-1) + b] += value phi_a(y1_m) phi_b(y2_m), and the same
    /// with `unoccluded_value` into unoccluded_sums. y1_m, y2_m: the sample's
    /// point on the light along the light's first and second tangent axes,
    /// metres from its centre. value: what is filtered, e.g. the light
    /// weight times the visibility (or a radiance); unoccluded_value: the
    /// value the sample would have had unoccluded, whose filtered sums
    /// normalise the result (a fully lit region stays exactly lit). Each
    /// array holds channels() doubles.
    void accumulate(double y1_m, double y2_m, double value, double unoccluded_value, double *value_sums,
                    double *unoccluded_sums) const;

  private:
    int pairs_ = 1;
    std::array<double, kMaafMaxPairs> centre_y_rad_per_m_{};  ///< C_y^p, index p (0 unused)
};

}  // namespace aaf
