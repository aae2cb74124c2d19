#include "aaf/core/methods/maaf/maaf_fitted_weights.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <mutex>
#include <string>
#include <tuple>

#include "aaf/core/methods/maaf/maaf_components.h"
#include "aaf/core/util/error.h"

namespace aaf {

namespace {

constexpr int kSlopeNodes = 9;           ///< tau nodes of the fit
constexpr int kFrequencyNodes = 320;     ///< W nodes of the fit
constexpr double kFrequencyReach = 4.0;  ///< W up to this many times the wedge's x extent
constexpr int kRatioNodes = 33;          ///< t nodes of the table

/// Solves the small symmetric system m x = r (n <= 7) by Gaussian elimination with partial pivoting.
std::vector<double> solve(std::vector<double> m, std::vector<double> r, int n) {
    for (int c = 0; c < n; ++c) {
        int pivot = c;
        for (int i = c + 1; i < n; ++i)
            if (std::fabs(m[std::size_t(i * n + c)]) > std::fabs(m[std::size_t(pivot * n + c)])) pivot = i;
        for (int j = 0; j < n; ++j) std::swap(m[std::size_t(c * n + j)], m[std::size_t(pivot * n + j)]);
        std::swap(r[std::size_t(c)], r[std::size_t(pivot)]);
        const double d = m[std::size_t(c * n + c)];
        if (!(std::fabs(d) > 0)) continue;  // a null direction: that weight stays 0
        for (int i = c + 1; i < n; ++i) {
            const double f = m[std::size_t(i * n + c)] / d;
            for (int j = c; j < n; ++j) m[std::size_t(i * n + j)] -= f * m[std::size_t(c * n + j)];
            r[std::size_t(i)] -= f * r[std::size_t(c)];
        }
    }
    std::vector<double> x(std::size_t(n), 0.0);
    for (int i = n - 1; i >= 0; --i) {
        const double d = m[std::size_t(i * n + i)];
        if (!(std::fabs(d) > 0)) continue;
        double v = r[std::size_t(i)];
        for (int j = i + 1; j < n; ++j) v -= m[std::size_t(i * n + j)] * x[std::size_t(j)];
        x[std::size_t(i)] = v / d;
    }
    return x;
}

double truncated_gaussian_spectrum(double omega, double half_width, double sigma) {
    // Composite Simpson over [0, h] of the even density (phi is real).
    constexpr int kIntervals = 512;
    const double step = half_width / kIntervals;
    double num = 0, den = 0;
    for (int i = 0; i <= kIntervals; ++i) {
        const double y = i * step;
        const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        const double density = std::exp(-0.5 * y * y / (sigma * sigma));
        num += weight * density * std::cos(omega * y);
        den += weight * density;
    }
    return num / den;
}

}  // namespace

SampleSpectrum::SampleSpectrum(const SampleDensity &density) : density_(density) {
    if (!(density.half_width > 0) || !std::isfinite(density.half_width))
        throw Error("MAAF sample density: the half width must be positive and finite");
    if (density.shape == DensityShape::TruncatedGaussian &&
        (!(density.sigma > 0) || !std::isfinite(density.sigma)))
        throw Error("MAAF sample density: sigma must be positive and finite");
    constexpr int kSteps = 16384;
    const double reach = density.shape == DensityShape::CosineLobe ? 64.0 : 256.0 / density.half_width;
    table_step_ = reach / kSteps;
    table_.resize(kSteps + 1);
    for (int i = 0; i <= kSteps; ++i) table_[std::size_t(i)] = exact(i * table_step_);
}

double SampleSpectrum::exact(double omega) const {
    const double w = std::fabs(omega);
    switch (density_.shape) {
        case DensityShape::Uniform: {
            const double x = w * density_.half_width;
            return x < 1e-8 ? 1.0 : std::sin(x) / x;
        }
        case DensityShape::Semicircle: {
            const double x = w * density_.half_width;
            return x < 1e-8 ? 1.0 : 2.0 * std::cyl_bessel_j(1.0, x) / x;
        }
        case DensityShape::CosineLobe:
            return w < 1e-12 ? 1.0 : w > 700 ? 0.0 : w * std::cyl_bessel_k(1.0, w);
        case DensityShape::TruncatedGaussian:
            return truncated_gaussian_spectrum(w, density_.half_width, density_.sigma);
    }
    return 0.0;
}

double SampleSpectrum::operator()(double omega) const {
    const double at = std::fabs(omega) / table_step_;
    if (!(at < double(table_.size() - 1))) return exact(omega);
    const std::size_t i = std::size_t(at);
    const double f = at - double(i);
    return (1.0 - f) * table_[i] + f * table_[i + 1];
}

SampleDensity light_sample_density(const LightPlane &light) {
    const double half = 0.5 * std::sqrt(double(light.width_m) * double(light.height_m));
    if (light.profile == LightProfile::Uniform) return {DensityShape::Uniform, half, 1.0};
    return {DensityShape::TruncatedGaussian, half, double(light.sigma_m)};
}

std::vector<double> maaf_fit_pair_weights(const SampleSpectrum &phi, double omega_max, double t, int pairs,
                                          double k, MaafKernelForm form) {
    if (pairs < 2 || pairs > 8) throw Error("MAAF fitted weights: between 2 and 8 pairs");
    if (!(omega_max > 0) || !std::isfinite(omega_max) || !(k > 0) || !std::isfinite(k))
        throw Error("MAAF fitted weights: the band and k must be positive and finite");
    t = std::clamp(t, 0.0, 1.0);
    // s_min = 1: x scales with s_min and nothing else does, so this is every wedge of ratio t.
    const double s_max = t > 0 ? 1.0 / t : std::numeric_limits<double>::infinity();
    const std::vector<MaafComponent> c =
        maaf_pair_components(1.0, s_max, std::numeric_limits<double>::infinity(), omega_max, pairs);
    const int n = pairs - 1;
    std::vector<double> a(static_cast<std::size_t>(pairs)), dc(static_cast<std::size_t>(pairs));
    const bool maaf6 = form == MaafKernelForm::Maaf6;
    for (int p = 0; p < pairs; ++p) {
        const double sigma_x = c[std::size_t(p)].sigma_x;
        a[std::size_t(p)] = maaf6 ? k / sigma_x : 1.0 / (k * sigma_x);  // primal std (MaafKernelForm)
        const double r = c[std::size_t(p)].centre_x * a[std::size_t(p)];
        dc[std::size_t(p)] = maaf6 ? std::exp(-0.5 * r * r) : 0.0;  // e_p, the pair's DC correction
    }
    std::vector<double> normal(static_cast<std::size_t>(n * n), 0.0), rhs(static_cast<std::size_t>(n), 0.0),
        basis(static_cast<std::size_t>(n));
    const double w_step = kFrequencyReach * omega_max / kFrequencyNodes;  // the wedge's x extent is omega_max
    for (int j = 0; j < kSlopeNodes; ++j) {
        const double tau = t + (j + 0.5) * (1.0 - t) / kSlopeNodes;
        const double s = 1.0 / tau;
        for (int i = 0; i < kFrequencyNodes; ++i) {
            const double w = (i + 0.5) * w_step;
            const double target = phi(w * s);
            const double g0 = std::exp(-0.5 * (w * a[0]) * (w * a[0]));
            const double residual = (g0 * target - target) / w;  // the central alone, relative to a_0
            for (int p = 1; p < pairs; ++p) {
                const MaafComponent &cp = c[std::size_t(p)];
                const double ap = a[std::size_t(p)];
                const double lo = std::exp(-0.5 * ((w - cp.centre_x) * ap) * ((w - cp.centre_x) * ap));
                const double hi = std::exp(-0.5 * ((w + cp.centre_x) * ap) * ((w + cp.centre_x) * ap));
                const double mid = std::exp(-0.5 * (w * ap) * (w * ap));
                const double phi_lo = phi(w * s - cp.centre_y), phi_hi = phi(w * s + cp.centre_y);
                const double gain = maaf6 ? ap / a[0] : 1.0;  // the component's Fourier peak, central's 1
                basis[std::size_t(p - 1)] =
                    gain * (lo * phi_lo + hi * phi_hi - dc[std::size_t(p)] * mid * (phi_lo + phi_hi)) / w;
            }
            for (int p = 0; p < n; ++p) {
                rhs[std::size_t(p)] -= basis[std::size_t(p)] * residual;
                for (int q = 0; q < n; ++q)
                    normal[std::size_t(p * n + q)] += basis[std::size_t(p)] * basis[std::size_t(q)];
            }
        }
    }
    double trace = 0;
    for (int p = 0; p < n; ++p) trace += normal[std::size_t(p * n + p)];
    for (int p = 0; p < n; ++p)
        normal[std::size_t(p * n + p)] += 1e-12 * trace;  // keeps a null direction at 0
    return solve(normal, rhs, n);
}

MaafFittedWeights::MaafFittedWeights(const SampleDensity &density, double omega_max, int pairs, double k,
                                     MaafKernelForm form)
    : pairs_(pairs) {
    if (!(omega_max > 0) || !std::isfinite(omega_max))
        throw Error("MAAF fitted weights: the band must be positive and finite");
    SampleDensity scaled = density;
    if (scaled.half_width == 0) scaled.half_width = 2.0 / omega_max;
    const SampleSpectrum phi(scaled);
    const int n = pairs - 1;
    table_.resize(kRatioNodes * static_cast<std::size_t>(std::max(n, 0)));
    for (int ti = 0; ti < kRatioNodes; ++ti) {
        const std::vector<double> mu =
            maaf_fit_pair_weights(phi, omega_max, double(ti) / (kRatioNodes - 1), pairs, k, form);
        std::copy(mu.begin(), mu.end(), table_.begin() + std::ptrdiff_t(ti * n));
    }
}

void MaafFittedWeights::weights(double t, double *mu) const {
    const int n = pairs_ - 1;
    const double at = std::clamp(t, 0.0, 1.0) * (kRatioNodes - 1);
    const int t0 = std::min(int(at), kRatioNodes - 2);
    const double f = at - t0;
    for (int p = 0; p < n; ++p)
        mu[p] = (1 - f) * table_[std::size_t(t0 * n + p)] + f * table_[std::size_t((t0 + 1) * n + p)];
}

std::shared_ptr<const MaafFittedWeights> shared_fitted_weights(const SampleDensity &density, double omega_max,
                                                               int pairs, double k, MaafKernelForm form) {
    using Key = std::tuple<DensityShape, double, double, double, int, double, MaafKernelForm>;
    struct Entry {
        Key key;
        std::shared_ptr<const MaafFittedWeights> table;
    };
    constexpr std::size_t kKept = 32;
    static std::mutex mutex;
    static std::deque<Entry> kept;  // oldest first
    const Key key{density.shape, density.half_width, density.sigma, omega_max, pairs, k, form};
    const auto find = [&]() -> std::shared_ptr<const MaafFittedWeights> {
        for (const Entry &entry : kept)
            if (entry.key == key) return entry.table;
        return nullptr;
    };
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (auto table = find()) return table;
    }
    // Built outside the lock: other layers and callers are not held up. Two
    // callers may build the same table at once; both results are equal.
    auto built = std::make_shared<const MaafFittedWeights>(density, omega_max, pairs, k, form);
    const std::lock_guard<std::mutex> lock(mutex);
    if (auto table = find()) return table;
    if (kept.size() == kKept) kept.pop_front();
    kept.push_back({key, built});
    return built;
}

}  // namespace aaf
