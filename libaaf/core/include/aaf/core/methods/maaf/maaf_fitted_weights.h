#pragma once

#include <memory>
#include <vector>

#include "aaf/core/contract/light_plane.h"

namespace aaf {

/// The distribution the samples of one MAAF coordinate (y on the light, y as
/// a bounce direction, u on the lens) are drawn from, projected on one axis.
/// The maaf6 filter has no y or u envelope of its own: the sampling density
/// is the envelope (Maaf6SampleSide), so its spectrum, the density's
/// characteristic function, is the filter's response along Omega_y.
enum class DensityShape {
    Uniform,            ///< uniform on [-half_width, half_width] (a uniform rectangular light)
    TruncatedGaussian,  ///< exp(-y^2 / (2 sigma^2)) on [-half_width, half_width] (a Gaussian light)
    Semicircle,         ///< a uniform disc of radius half_width seen along one axis (the lens)
    CosineLobe,         ///< cosine-weighted directions as tan theta along one axis (indirect light)
};

struct SampleDensity {
    DensityShape shape = DensityShape::Uniform;
    /// y units (metres on a light or lens); unused by CosineLobe. 0: 2 / Omega^max of the
    /// band it is used with (MaafFittedWeights), the toolkit's uniform light (Omega_y^max =
    /// 2 / sigma with sigma = half the side).
    double half_width = 0;
    double sigma = 1;  ///< TruncatedGaussian only
};

/// A light's y seen along one of its axes (or a receiver's tangent axis that
/// follows them): one density for both axes, of the light's geometric-mean
/// half side; Uniform or TruncatedGaussian as its emission profile.
SampleDensity light_sample_density(const LightPlane &light);

/// The density's characteristic function phi(omega) = E[cos(omega y)]
/// (phi(0) = 1, even): sin(w h) / (w h) for Uniform; 2 J1(w h) / (w h) for
/// Semicircle; |w| K1(|w|) for CosineLobe (the marginal 1 / (2 (1 + y^2)^1.5)
/// of the density 1 / (pi (1 + r^2)^2) that cosine-weighted directions have
/// on the unit plane above the receiver); TruncatedGaussian by quadrature.
/// omega in rad per y unit. exact() evaluates it; operator() interpolates a
/// table of it built at construction (16384 steps up to 256 / h, 64 for
/// CosineLobe; exact() beyond), which the fits evaluate a million times.
class SampleSpectrum {
  public:
    explicit SampleSpectrum(const SampleDensity &density);
    double exact(double omega) const;
    double operator()(double omega) const;

  private:
    SampleDensity density_;
    double table_step_ = 0;
    std::vector<double> table_;  ///< exact(i * table_step_)
};

/// How a filter realises its components along x, which the fit matches.
enum class MaafKernelForm {
    /// maaf6_x_kernel(): primal std a_p = k / sigma_x^p, each pair made zero-mean (e_p).
    Maaf6,
    /// maaf_filter() (4D): primal std a_p = 1 / (k sigma_x^p) weighted by sigma_x^p (MAAF Eq. 21), so
    /// every component's Fourier peak is mu_p times the central's (the a_p / a_0 below is 1), and
    /// no DC correction (e_p = 0).
    Maaf4D,
};

/// Pair weights mu_1 .. mu_{N-1} fitted so that the maaf6 filter's response
/// along the wedge matches the sampling density's spectrum (mu_0 = 1).
///
/// Why. The filter realises component p (MAAF Eq. 11-13) with the x kernel of
/// maaf6_x_kernel() and, along y, the sampling density times cos / sin(C_y^p y).
/// On a wedge line Omega_y = s Omega_x (slope s) its response is therefore,
/// with a_p = k / sigma_x^p the primal std and phi the density's spectrum,
///   H_s(W) = [a_0 G(W a_0) phi(W s) + sum_p mu_p a_p (G((W - C_x) a_p) phi(W s - C_y)
///             + G((W + C_x) a_p) phi(W s + C_y) - e_p G(W a_p) (phi(W s - C_y) + phi(W s + C_y)))] / a_0,
/// G(z) = e^{-z^2 / 2},
/// e_p the pair's DC correction, while the light integral that the pixel
/// should get passes phi(W s) whatever W: the ideal filter is phi(Omega_y)
/// on the whole wedge (MAAF Eq. 14's accuracy, with the density's spectrum
/// as the target). MAAF Eq. 10's mu_p ignore that the components overlap through
/// phi and that each realised component's Fourier peak is a_p / a_0 of the
/// central's: on room's converged shadows they darkened smooth penumbrae by
/// about 2% (scripts/study/RESULTS_MAAF6.md).
///
/// The fit. mu minimises sum over slopes s and frequencies W of
/// (H_s(W) - phi(W s))^2 / W^2 (the 1 / W^2: an edge's spectrum, so this is
/// the squared error of filtered edges), s = 1 / tau with tau uniform over
/// [s_min / s_max, 1] (uniform over the wedge's area at each Omega_y, as
/// MAAF Eq. 14 weighs it), W over (0, 4 Omega_y^max / s_min]. Everything scales with
/// s_min and Omega_y^max, so the weights depend only on t = s_min / s_max,
/// q = (the density's scale) x Omega_y^max, N and k. The 4D filter is fitted
/// alike per light axis, with its own kernel form (MaafKernelForm::Maaf4D).
class MaafFittedWeights {
  public:
    /// A table over t in [0, 1] (33 nodes) for a layer whose density is
    /// `density` (half_width 0: 2 / omega_max) and whose band is omega_max (per
    /// y unit): q = density scale x omega_max. pairs: N (2 .. 8); k: as Maaf6FilterParams::k. Throws
    /// aaf::Error on non-positive or non-finite arguments.
    MaafFittedWeights(const SampleDensity &density, double omega_max, int pairs, double k,
                      MaafKernelForm form = MaafKernelForm::Maaf6);

    /// mu_1 .. mu_{N-1} into mu[0 .. N-2] for a wedge of slope ratio t =
    /// s_min / s_max (clamped to [0, 1]), interpolated linearly in t.
    void weights(double t, double *mu) const;

    int pairs() const { return pairs_; }

  private:
    int pairs_ = 1;
    std::vector<double> table_;  ///< [t node][p - 1]
};

/// The table MaafFittedWeights(density, omega_max, pairs, k) builds, kept
/// for the process: a sequence's frames, the two layers' lens wedges and
/// repeated calls share one table instead of each paying for the density's
/// spectrum and 33 fits (about 0.05 s each, more than the rest of a small frame's
/// filter). The table is a function of the arguments alone, so a shared one
/// has the bits a fresh one would. The last 32 argument sets are kept;
/// thread-safe. Throws as the constructor.
std::shared_ptr<const MaafFittedWeights> shared_fitted_weights(const SampleDensity &density, double omega_max,
                                                               int pairs, double k,
                                                               MaafKernelForm form = MaafKernelForm::Maaf6);

/// One fit (MaafFittedWeights' "The fit"): mu_1 .. mu_{N-1} for slope ratio
/// t in [0, 1], the density's spectrum `spectrum` and the band omega_max it is
/// partitioned with (per y unit). Exposed for tests.
std::vector<double> maaf_fit_pair_weights(const SampleSpectrum &spectrum, double omega_max, double t,
                                          int pairs, double k, MaafKernelForm form = MaafKernelForm::Maaf6);

}  // namespace aaf
