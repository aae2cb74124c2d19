// The sampling densities' spectra and the pair weights fitted to them
// (aaf::SampleSpectrum, aaf::MaafFittedWeights).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

#include "aaf/core/methods/maaf/maaf_fitted_weights.h"
#include "aaf/core/util/error.h"

using namespace aaf;

TEST_CASE("MAAF sample spectra: each density's characteristic function, by hand", "[maaf6]") {
    // sin(1) / 1, 2 J1(1) / 1 and 1 K1(1) from tables (Abramowitz & Stegun 9.1, 9.8).
    CHECK(SampleSpectrum({DensityShape::Uniform, 2.0, 1.0}).exact(0.5) == Approx(0.8414709848).epsilon(1e-9));
    CHECK(SampleSpectrum({DensityShape::Semicircle, 1.0, 1.0}).exact(-1.0) ==
          Approx(2 * 0.4400505857).epsilon(1e-9));
    CHECK(SampleSpectrum({DensityShape::CosineLobe, 1.0, 1.0}).exact(1.0) ==
          Approx(0.6019072302).epsilon(1e-9));
    for (DensityShape shape : {DensityShape::Uniform, DensityShape::Semicircle, DensityShape::CosineLobe,
                               DensityShape::TruncatedGaussian}) {
        const SampleSpectrum phi({shape, 1.0, 0.5});
        CHECK(phi(0.0) == Approx(1.0).epsilon(1e-12));
        // The interpolated table the fits use, against the exact function, inside and beyond its reach.
        for (double w : {0.013, 0.7, 2.8, 9.1, 33.3, 300.0})
            CHECK(phi(w) == Approx(phi.exact(w)).margin(1e-4));
    }
    // A Gaussian cut at 8 sigma is the Gaussian's exp(-(w sigma)^2 / 2); one of huge sigma is uniform.
    CHECK(SampleSpectrum({DensityShape::TruncatedGaussian, 0.8, 0.1}).exact(10.0) ==
          Approx(std::exp(-0.5)).epsilon(1e-5));
    CHECK(SampleSpectrum({DensityShape::TruncatedGaussian, 1.0, 1e4}).exact(2.0) ==
          Approx(std::sin(2.0) / 2.0).epsilon(1e-5));
}

TEST_CASE("MAAF sample spectra: the lens and the cosine lobe match the samples the tracer draws", "[maaf6]") {
    // Monte Carlo of E[cos(w v)]: v the x of a point uniform on the unit disc (the lens), and
    // v = tan(theta) cos(phi) of a cosine-weighted direction (a bounce, on the unit plane above).
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int n = 400000;
    const double omegas[] = {0.7, 2.8};
    double disc[2] = {0, 0}, lobe[2] = {0, 0};
    for (int i = 0; i < n; ++i) {
        const double r = std::sqrt(unit(rng)), phi = 2 * 3.14159265358979 * unit(rng);
        const double x =
            r * std::cos(phi);  // the disc's point; Malley: the same point lifted is a cosine direction
        const double tan_theta = r / std::sqrt(1 - r * r);
        for (int k = 0; k < 2; ++k) {
            disc[k] += std::cos(omegas[k] * x) / n;
            lobe[k] += std::cos(omegas[k] * tan_theta * std::cos(phi)) / n;
        }
    }
    for (int k = 0; k < 2; ++k) {
        INFO("omega " << omegas[k]);
        CHECK(SampleSpectrum({DensityShape::Semicircle, 1.0, 1.0})(omegas[k]) ==
              Approx(disc[k]).margin(0.005));
        CHECK(SampleSpectrum({DensityShape::CosineLobe, 1.0, 1.0})(omegas[k]) ==
              Approx(lobe[k]).margin(0.005));
    }
}

TEST_CASE("MAAF fitted weights: the table holds the fit at its nodes and is linear between them", "[maaf6]") {
    const SampleDensity light{DensityShape::Uniform, 0.05, 1.0};
    const MaafFittedWeights table(light, 40.0, 3, 1.0);
    const SampleSpectrum phi(light);
    const std::vector<double> at_half = maaf_fit_pair_weights(phi, 40.0, 0.5, 3, 1.0);  // node 16 of 32
    const std::vector<double> at_next = maaf_fit_pair_weights(phi, 40.0, 17.0 / 32.0, 3, 1.0);
    double mu[2];
    table.weights(0.5, mu);
    CHECK(mu[0] == at_half[0]);
    CHECK(mu[1] == at_half[1]);
    table.weights(16.5 / 32.0, mu);
    CHECK(mu[0] == Approx(0.5 * (at_half[0] + at_next[0])).epsilon(1e-12));
    CHECK(mu[1] == Approx(0.5 * (at_half[1] + at_next[1])).epsilon(1e-12));
    // Only t = s_min / s_max and q = (density scale) Omega_y^max matter: the same light twice as
    // wide with half the band gives the same weights.
    const std::vector<double> scaled =
        maaf_fit_pair_weights(SampleSpectrum({DensityShape::Uniform, 0.1, 1.0}), 20.0, 0.5, 3, 1.0);
    CHECK(scaled[0] == Approx(at_half[0]).epsilon(1e-9));
    CHECK(scaled[1] == Approx(at_half[1]).epsilon(1e-9));
    CHECK_THROWS(MaafFittedWeights(light, 0.0, 3, 1.0));
    CHECK_THROWS(maaf_fit_pair_weights(phi, 40.0, 0.5, 1, 1.0));
}

TEST_CASE(
    "MAAF fitted weights: a Gaussian light's wider spectrum gets smaller outer weights than a uniform one's",
    "[maaf6]") {
    // Same band Omega_y^max = 2 / 0.05: a uniform light of half side 5 cm passes sinc(C_y h) at the
    // outer pair's C_y = 0.8 Omega_y^max (sinc(1.6) = 0.62), a Gaussian of sigma 5 cm exp(-(1.6)^2 / 2)
    // = 0.28 (MAAF Eq. 10 gives both 0.73). The fit follows the spectrum the filter has to pass.
    const std::vector<double> uniform =
        maaf_fit_pair_weights(SampleSpectrum({DensityShape::Uniform, 0.05, 1.0}), 40.0, 1.0, 3, 1.0);
    const std::vector<double> gaussian = maaf_fit_pair_weights(
        SampleSpectrum({DensityShape::TruncatedGaussian, 0.4, 0.05}), 40.0, 1.0, 3, 1.0);
    INFO("uniform " << uniform[0] << " " << uniform[1] << ", Gaussian " << gaussian[0] << " " << gaussian[1]);
    CHECK(gaussian[1] < uniform[1] - 0.2);
}

TEST_CASE("MAAF fitted weights: the process-wide tables equal fresh ones, shared by equal arguments",
          "[maaf6]") {
    const SampleDensity gaussian{DensityShape::TruncatedGaussian, 0.5, 0.25};
    const auto same_weights = [](const MaafFittedWeights &a, const MaafFittedWeights &b) {
        REQUIRE(a.pairs() == b.pairs());
        for (double t : {0.0, 0.031, 0.5, 0.77, 1.0}) {
            double mu_a[8] = {}, mu_b[8] = {};
            a.weights(t, mu_a);
            b.weights(t, mu_b);
            for (int p = 0; p + 1 < a.pairs(); ++p)
                if (mu_a[p] != mu_b[p]) return false;  // bit for bit
        }
        return true;
    };
    const auto first = shared_fitted_weights(gaussian, 3.0, 3, 1.0);
    CHECK(same_weights(*first, MaafFittedWeights(gaussian, 3.0, 3, 1.0)));
    CHECK(shared_fitted_weights(gaussian, 3.0, 3, 1.0) == first);  // built once
    // Any argument that changes the table gives another one.
    CHECK(shared_fitted_weights(gaussian, 3.0, 4, 1.0) != first);
    CHECK(shared_fitted_weights(gaussian, 3.0, 3, 0.5) != first);
    CHECK(shared_fitted_weights(gaussian, 2.0, 3, 1.0) != first);
    CHECK(shared_fitted_weights({DensityShape::Uniform, 0.5, 0.25}, 3.0, 3, 1.0) != first);
    CHECK(shared_fitted_weights({DensityShape::TruncatedGaussian, 0.5, 0.3}, 3.0, 3, 1.0) != first);
    // Many callers at once (the two layers, a library's own threads) get equal tables.
    std::vector<std::shared_ptr<const MaafFittedWeights>> got(8);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < got.size(); ++i)
        threads.emplace_back(
            [&, i] { got[i] = shared_fitted_weights(gaussian, 5.0 + double(i % 2), 3, 1.0); });
    for (std::thread &thread : threads) thread.join();
    for (std::size_t i = 0; i < got.size(); ++i)
        CHECK(same_weights(*got[i], MaafFittedWeights(gaussian, 5.0 + double(i % 2), 3, 1.0)));
    // Past 32 other argument sets the first is forgotten and rebuilt, with the same bits.
    for (int i = 0; i < 40; ++i) shared_fitted_weights({DensityShape::Uniform, 0.5, 1.0}, 1.0 + i, 2, 1.0);
    const auto rebuilt = shared_fitted_weights(gaussian, 3.0, 3, 1.0);
    CHECK(rebuilt != first);
    CHECK(same_weights(*rebuilt, *first));
    // Bad arguments still throw, and nothing is kept for them.
    CHECK_THROWS_AS(shared_fitted_weights(gaussian, 0.0, 3, 1.0), Error);
}
