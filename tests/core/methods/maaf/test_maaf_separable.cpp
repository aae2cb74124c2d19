// maaf_separable_filter() (vector kernels, float, polynomial sin/cos and
// exp) against its two passes written out from the equations in double
// with std::exp, std::cos and std::sin, on varied per-pixel kernels, guides
// and sums.
#include <catch2/catch.hpp>

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "aaf/core/methods/maaf/maaf_separable.h"

using namespace aaf;

namespace {

constexpr int kPairs = 3;
constexpr int kPerAxis = 2 * kPairs - 1;  // functions per light axis (maaf_accumulation.h)

/// A frame of guides, kernels and sums with every case the passes treat
/// apart: two objects, normals beyond the threshold, unusable pixels,
/// unfiltered pixels, kernels and reaches that differ from pixel to pixel.
struct RandomFrame {
    int width = 45, height = 38;
    GatherGuides guides;
    std::vector<MaafPixelKernel> kernels;
    std::vector<std::vector<float>> values, unoccludeds;

    RandomFrame() {
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        guides.resize(width, height);
        const std::size_t n = std::size_t(width) * std::size_t(height);
        kernels.resize(n);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t i = guides.index(x, y);
                // A curved receiver: coordinates not linear in the pixel, 1 cm per pixel.
                guides.coord_u_m[i] =
                    0.01f * float(x) + 0.003f * std::sin(0.2f * float(y)) + 0.001f * unit(rng);
                guides.coord_v_m[i] = 0.01f * float(y) + 0.002f * std::cos(0.3f * float(x));
                const float tilt = unit(rng) < 0.05f ? 0.8f : 0.05f * unit(rng);  // some beyond 20 degrees
                guides.normal_x[i] = std::sin(tilt);
                guides.normal_y[i] = std::cos(tilt);
                guides.normal_z[i] = 0.0f;
                guides.object_id[i] = unit(rng) < 0.02f ? std::nanf("") : x < 30 ? 1.0f : 2.0f;
                MaafPixelKernel &k = kernels[i];
                k.filtered = unit(rng) < 0.9f;
                for (int p = 0; p < kPairs; ++p) {
                    const float std_m = 0.01f + 0.04f * unit(rng) / float(p + 1);
                    k.inv_two_sigma_sq[p] = 1.0f / (2.0f * std_m * std_m);
                    k.radius_px[p] = std::min(12, int(std::ceil(3.0f * std_m / 0.01f)));
                    k.omega_x[p] = p == 0 ? 0.0f : 150.0f * float(p) * (0.5f + unit(rng));
                    k.weight[p] = 0.5 + double(unit(rng));
                }
            }
        values.assign(std::size_t(kPerAxis * kPerAxis), std::vector<float>(n));
        unoccludeds = values;
        for (std::size_t c = 0; c < values.size(); ++c)
            for (std::size_t i = 0; i < n; ++i) {
                values[c][i] = c == 0 ? unit(rng) : 2.0f * unit(rng) - 1.0f;
                unoccludeds[c][i] = c == 0 ? 1.0f + unit(rng) : 2.0f * unit(rng) - 1.0f;
            }
    }
};

/// One term of the regrouped MAAF Eq. 13 (maaf_separable.cpp): its complex
/// sources from the channels, and its kernel's components and sign.
struct RefTerm {
    int pu, pv;
    double sign_v, scale;
    std::vector<std::pair<double, int>> re, im;
};

std::vector<RefTerm> ref_terms() {
    auto ch = [](int fu, int fv) { return fu * kPerAxis + fv; };
    std::vector<RefTerm> terms{{0, 0, 1, 1, {{1, ch(0, 0)}}, {}}};
    for (int p = 1; p < kPairs; ++p) {
        terms.push_back({p, 0, 1, 1, {{1, ch(2 * p - 1, 0)}}, {{1, ch(2 * p, 0)}}});
        terms.push_back({0, p, 1, 1, {{1, ch(0, 2 * p - 1)}}, {{1, ch(0, 2 * p)}}});
    }
    for (int p = 1; p < kPairs; ++p)
        for (int q = 1; q < kPairs; ++q) {
            const int cc = ch(2 * p - 1, 2 * q - 1), cs = ch(2 * p - 1, 2 * q), sc = ch(2 * p, 2 * q - 1),
                      ss = ch(2 * p, 2 * q);
            terms.push_back({p, q, 1, 0.5, {{1, cc}, {-1, ss}}, {{1, cs}, {1, sc}}});
            terms.push_back({p, q, -1, 0.5, {{1, cc}, {1, ss}}, {{1, sc}, {-1, cs}}});
        }
    return terms;
}

/// The passes in double: the vertical with each pixel's kernels, the
/// horizontal with each centre's over the vertical's output, then MAAF Eq. 21.
MaafFilteredSums reference(const RandomFrame &f) {
    const GatherGuides &g = f.guides;
    const std::vector<RefTerm> terms = ref_terms();
    const std::size_t n = f.kernels.size(), count = terms.size();
    const double cos_threshold = std::cos(20.0 * 3.14159265358979323846 / 180.0);
    auto accepted = [&](std::size_t c, std::size_t t) {
        const double cos_angle = double(g.normal_x[c]) * g.normal_x[t] +
                                 double(g.normal_y[c]) * g.normal_y[t] +
                                 double(g.normal_z[c]) * g.normal_z[t];
        return t == c || (g.object_id[t] == g.object_id[c] && cos_angle >= cos_threshold);
    };
    auto weight = [&](std::size_t c, std::size_t t, const RefTerm &term, int offset) {
        const MaafPixelKernel &k = f.kernels[c];
        if (!k.filtered || offset > std::max(k.radius_px[term.pu], k.radius_px[term.pv]))
            return std::complex<double>(0.0);
        const double du = double(g.coord_u_m[t]) - g.coord_u_m[c],
                     dv = double(g.coord_v_m[t]) - g.coord_v_m[c];
        const double gauss =
            std::exp(-du * du * k.inv_two_sigma_sq[term.pu] - dv * dv * k.inv_two_sigma_sq[term.pv]);
        const double phase = double(k.omega_x[term.pu]) * du + term.sign_v * double(k.omega_x[term.pv]) * dv;
        return gauss * std::complex<double>(std::cos(phase), std::sin(phase));  // MAAF Eq. 12, 13
    };
    auto source = [&](const RefTerm &term, const std::vector<std::vector<float>> &sums, std::size_t i) {
        std::complex<double> s;
        for (const auto &[factor, c] : term.re) s += factor * double(sums[std::size_t(c)][i]);
        for (const auto &[factor, c] : term.im)
            s += std::complex<double>(0, factor * double(sums[std::size_t(c)][i]));
        return s;
    };
    std::vector<std::complex<double>> vertical(2 * count * n);  // value, unoccluded per term
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const std::size_t c = g.index(x, y);
            for (std::size_t j = 0; j < count; ++j) {
                std::complex<double> value, unoccluded;
                if (!f.kernels[c].filtered) {  // keeps its sources
                    value = source(terms[j], f.values, c);
                    unoccluded = source(terms[j], f.unoccludeds, c);
                }
                for (int ty = 0; ty < f.height && f.kernels[c].filtered; ++ty) {
                    const std::size_t t = g.index(x, ty);
                    if (!accepted(c, t)) continue;
                    const std::complex<double> w = weight(c, t, terms[j], std::abs(ty - y));
                    value += w * source(terms[j], f.values, t);
                    unoccluded += w * source(terms[j], f.unoccludeds, t);
                }
                vertical[(2 * j) * n + c] = value;
                vertical[(2 * j + 1) * n + c] = unoccluded;
            }
        }
    MaafFilteredSums out{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n),
                         std::vector<double>(n)};
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const std::size_t c = g.index(x, y);
            const MaafPixelKernel &k = f.kernels[c];
            for (std::size_t j = 0; j < count && k.filtered; ++j) {
                double value = 0, unoccluded = 0;
                for (int tx = 0; tx < f.width; ++tx) {
                    const std::size_t t = g.index(tx, y);
                    if (!accepted(c, t)) continue;
                    const std::complex<double> w = weight(c, t, terms[j], std::abs(tx - x));
                    value += (w * vertical[(2 * j) * n + t]).real();
                    unoccluded += (w * vertical[(2 * j + 1) * n + t]).real();
                }
                const double scale =
                    terms[j].scale * k.weight[terms[j].pu] * k.weight[terms[j].pv];  // MAAF Eq. 21
                out.numerator[c] += scale * value;
                out.denominator[c] += scale * unoccluded;
                if (j == 0) {
                    out.central_numerator[c] = value;
                    out.central_denominator[c] = unoccluded;
                }
            }
        }
    return out;
}

}  // namespace

TEST_CASE("Separable MAAF's vector passes match the equations in double within 1e-6 of the largest sum",
          "[maaf][filter]") {
    const RandomFrame frame;
    const MaafFilteredSums expected = reference(frame);
    MaafFilteredSums one, two;
    tbb::task_arena(1).execute([&] {
        one = maaf_separable_filter(frame.guides, 20.0f, frame.kernels, kPairs, kPairs, frame.values,
                                    frame.unoccludeds);
    });
    tbb::task_arena(2).execute([&] {
        two = maaf_separable_filter(frame.guides, 20.0f, frame.kernels, kPairs, kPairs, frame.values,
                                    frame.unoccludeds);
    });
    CHECK(one.numerator == two.numerator);  // the same bits for any thread count
    CHECK(one.denominator == two.denominator);
    const std::vector<double> MaafFilteredSums::*members[] = {
        &MaafFilteredSums::numerator, &MaafFilteredSums::denominator, &MaafFilteredSums::central_numerator,
        &MaafFilteredSums::central_denominator};
    for (const auto member : members) {
        const std::vector<double> &want = expected.*member, &got = one.*member;
        double largest = 0, worst = 0;
        for (std::size_t i = 0; i < want.size(); ++i) {
            if (!frame.kernels[i].filtered) continue;
            largest = std::max(largest, std::abs(want[i]));
            worst = std::max(worst, std::abs(got[i] - want[i]));
        }
        INFO("largest " << largest << ", worst difference " << worst);
        CHECK(largest > 1.0);
        // Float sums over up to 25 x 25 taps of 13 terms, sin/cos and exp to about 1e-7 (measured: see
        // README).
        CHECK(worst <= 1e-6 * largest);
    }
}
