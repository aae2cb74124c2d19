// The gather's SIMD rows (gather_rows.h, Google Highway runtime dispatch):
// every instruction set this build carries gives its kind's bits (fused
// multiply-adds or not), and they agree with a plain double-precision sum
// of the documented weights.
#include <hwy/targets.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../../unpinned_instruction_set.h"
#include "aaf/core/kernels/fast_exp.h"
#include "aaf/core/kernels/gather.h"
#include "aaf/core/kernels/gather_rows.h"
#include "aaf/core/util/thread_count.h"

using namespace aaf;

namespace {

/// Guides with everything the kernels branch on: radii 0 to 7 (some reaching
/// past the edges), two objects, a NaN id, zero and tilted normals, widths
/// that vary per pixel; optionally the shear planes. With `extremes`, pixels
/// whose taps' exponents are NaN (a NaN coordinate), -inf (an infinite one)
/// or -0 (zero width), all accepted by their neighbours' tests: the
/// exponential's clamps must give the scalar function's bits for them.
GatherGuides varied_guides(int width, int height, bool sheared, bool anisotropic = false,
                           bool extremes = false) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    GatherGuides g;
    g.resize(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = g.index(x, y);
            g.coord_u_m[i] = 0.01f * x + 0.002f * unit(rng);
            g.coord_v_m[i] = 0.01f * y + 0.002f * unit(rng);
            const float tilt = 0.6f * unit(rng);
            g.normal_x[i] = std::sin(tilt);
            g.normal_z[i] = std::cos(tilt);
            g.object_id[i] = x < width / 2 ? 1.0f : 2.0f;
            g.inv_two_sigma_sq[i] = 1.0f / (2.0f * std::pow(0.01f + 0.03f * unit(rng), 2.0f));
            g.radius_px[i] = int(8 * unit(rng));
        }
    g.object_id[g.index(3, 2)] = std::nanf("");
    g.normal_x[g.index(5, 4)] = g.normal_z[g.index(5, 4)] = 0.0f;
    if (extremes) {
        g.coord_u_m[g.index(6, 1)] = std::nanf("");
        g.coord_v_m[g.index(9, 7)] = std::numeric_limits<float>::infinity();
        g.coord_u_m[g.index(20, 9)] = -std::numeric_limits<float>::infinity();
        g.inv_two_sigma_sq[g.index(10, 3)] = 0.0f;
        g.inv_two_sigma_sq[g.index(11, 5)] = 0.0f;
        g.radius_px[g.index(10, 3)] = g.radius_px[g.index(11, 5)] = 5;
    }
    if (anisotropic) {  // a second width along v (AAF: one band-limit per light axis)
        g.inv_two_sigma_sq_v.resize(g.coord_u_m.size());
        for (float &w : g.inv_two_sigma_sq_v) w = 1.0f / (2.0f * std::pow(0.005f + 0.03f * unit(rng), 2.0f));
    }
    if (sheared) {
        g.coord_n_m.resize(g.coord_u_m.size());
        g.shear_u.resize(g.coord_u_m.size());
        g.shear_v.resize(g.coord_u_m.size());
        g.inv_two_sigma_sq_n.resize(g.coord_u_m.size());
        for (std::size_t i = 0; i < g.coord_n_m.size(); ++i) {
            g.coord_n_m[i] = 0.05f * unit(rng);
            g.shear_u[i] = unit(rng) - 0.5f;
            g.shear_v[i] = unit(rng) - 0.5f;
            g.inv_two_sigma_sq_n[i] = unit(rng) < 0.3f ? 0.0f : 0.5f * g.inv_two_sigma_sq[i] * unit(rng);
        }
    }
    return g;
}

/// gather() of `channels` noise planes, the outputs concatenated.
std::vector<float> run(const GatherGuides &g, GatherMode mode, int channels) {
    const std::size_t n = std::size_t(g.width) * g.height;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<std::vector<float>> sources(channels, std::vector<float>(n)), outputs = sources;
    std::vector<ConstPlaneView> in;
    std::vector<PlaneView> out;
    for (int k = 0; k < channels; ++k) {
        for (float &v : sources[k]) v = unit(rng);
        in.push_back(plane_view(sources[k].data(), g.width, g.height));
        out.push_back(plane_view(outputs[k].data(), g.width, g.height));
    }
    GatherSettings settings;
    settings.mode = mode;
    gather(g, settings, in, out);
    std::vector<float> all;
    for (const std::vector<float> &o : outputs) all.insert(all.end(), o.begin(), o.end());
    return all;
}

/// One 1D pass of the documented gather along x in double precision: the
/// normalised sum of accepted taps' exp(-(du^2 + dv^2) inv_two_sigma_sq).
double reference_along_x(const GatherGuides &g, const std::vector<float> &source, int x, int y,
                         float cos_threshold) {
    const std::size_t c = g.index(x, y);
    if (g.radius_px[c] == 0) return source[c];
    const int reach = std::min({g.radius_px[c], x, g.width - 1 - x});  // symmetric borders (the default)
    double sum = 0, weight_sum = 0;
    bool centre_counted = false;
    for (int tx = x - reach; tx <= x + reach; ++tx) {
        const std::size_t t = g.index(tx, y);
        const double cos_angle = double(g.normal_x[c]) * g.normal_x[t] +
                                 double(g.normal_y[c]) * g.normal_y[t] +
                                 double(g.normal_z[c]) * g.normal_z[t];
        if (!(g.object_id[t] == g.object_id[c] && cos_angle >= cos_threshold)) continue;
        if (t == c) centre_counted = true;
        const double du = g.coord_u_m[t] - g.coord_u_m[c], dv = g.coord_v_m[t] - g.coord_v_m[c];
        const double w = std::exp(-(du * du + dv * dv) * g.inv_two_sigma_sq[c]);
        sum += w * source[t];
        weight_sum += w;
    }
    if (!centre_counted) {
        sum += source[c];
        weight_sum += 1;
    }
    return sum / weight_sum;
}

}  // namespace

TEST_CASE("Gather SIMD: instruction sets that fuse alike give the same bits, the two kinds agree to rounding",
          "[gather][simd]") {
    const aaf_test::UnpinnedInstructionSet every_target;  // the test walks Highway's targets itself
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    REQUIRE(!targets.empty());
    for (const bool anisotropic : {false, true})
        for (const bool sheared : {false, true})
            for (const GatherMode mode : {GatherMode::Separable, GatherMode::Full2D})
                for (const int channels : {1, 3, 5}) {
                    // 29 columns: a partial vector at each row's end for every lane count.
                    const GatherGuides g = varied_guides(29, 13, sheared, anisotropic, true);
                    std::vector<float> first[2];  // per kind: rounded products, fused multiply-adds
                    std::set<std::string> names;
                    for (const std::int64_t target : targets) {
                        hwy::SetSupportedTargetsForTest(target);
                        names.insert(detail::gather_row_target());
                        const bool fuses = detail::gather_row_fuses();
                        const std::vector<float> result = run(g, mode, channels);
                        if (first[fuses].empty()) first[fuses] = result;
                        INFO("target " << hwy::TargetName(target) << ", anisotropic " << anisotropic
                                       << ", sheared " << sheared << ", channels " << channels << ", 2D "
                                       << (mode == GatherMode::Full2D));
                        CHECK(std::memcmp(result.data(), first[fuses].data(),
                                          result.size() * sizeof(float)) == 0);
                    }
                    hwy::SetSupportedTargetsForTest(0);
                    // Dispatch really switched: as many kernels ran as targets were offered.
                    CHECK(names.size() == targets.size());
                    // Where the build and machine have both kinds: the same
                    // weights up to a few roundings (sources lie in [0, 1]).
                    if (!first[0].empty() && !first[1].empty())
                        for (std::size_t i = 0; i < first[0].size(); ++i) {
                            INFO("output " << i << ": " << first[0][i] << " against " << first[1][i]);
                            CHECK(std::abs(first[0][i] - first[1][i]) <= 1e-6f);
                        }
                }
}

TEST_CASE("Gather SIMD: one 1D pass equals the documented weights summed in double", "[gather][simd]") {
    const aaf_test::UnpinnedInstructionSet every_target;  // the test walks Highway's targets itself
    // gather_row along x alone: the horizontal pass of the separable gather.
    const GatherGuides g = varied_guides(29, 13, false);
    const std::size_t n = std::size_t(g.width) * g.height;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> source(n), out(n);
    for (float &v : source) v = unit(rng);
    const float cos_threshold = std::cos(25.0f * 3.14159265358979323846f / 180.0f);
    detail::GatherSweep sweep;
    sweep.guides = &g;
    sweep.cos_threshold = cos_threshold;
    sweep.symmetric_borders = true;
    sweep.along_x = true;
    sweep.along_y = false;
    sweep.channels = 1;
    sweep.source[0] = source.data();
    sweep.output[0] = out.data();
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);
        for (int y = 0; y < g.height; ++y) detail::gather_row(sweep, y);
        for (int y = 0; y < g.height; ++y)
            for (int x = 0; x < g.width; ++x) {
                INFO("target " << hwy::TargetName(target) << " pixel " << x << ", " << y);
                // fast_exp's relative error (3e-7) and float sums of a few taps.
                CHECK(out[g.index(x, y)] ==
                      Approx(reference_along_x(g, source, x, y, cos_threshold)).epsilon(2e-6));
            }
    }
    hwy::SetSupportedTargetsForTest(0);
}

namespace {

/// One pass of the separable gather at pixel (x, y), along y or x, in
/// float, written out from its definition: taps from top to bottom (left to
/// right), the weight accepted * gather_exp(exponent) added one tap at a
/// time, the centre added back with weight 1 when its own test fails. The
/// SIMD kernels must give exactly these bits, with each multiply-add rounded
/// once where `fused` (std::fma) and the product rounded first elsewhere
/// (gather_row_fuses()).
float reference_pass(const GatherGuides &g, const float *source, int x, int y, bool along_y,
                     float cos_threshold, bool symmetric_borders, bool fused) {
    const auto mul_add = [fused](float a, float b, float c) { return fused ? std::fma(a, b, c) : a * b + c; };
    const std::size_t c = g.index(x, y);
    const int radius = g.radius_px[c];
    if (radius == 0) return source[c];
    int reach = radius;
    if (symmetric_borders)
        reach = along_y ? std::min({radius, y, g.height - 1 - y}) : std::min({radius, x, g.width - 1 - x});
    float sum = 0.0f, weight_sum = 0.0f;
    for (int o = -reach; o <= reach; ++o) {
        const int tx = along_y ? x : x + o, ty = along_y ? y + o : y;
        if (tx < 0 || tx >= g.width || ty < 0 || ty >= g.height) continue;
        const std::size_t t = g.index(tx, ty);
        const float cos_angle = mul_add(g.normal_z[c], g.normal_z[t],
                                        mul_add(g.normal_y[c], g.normal_y[t], g.normal_x[c] * g.normal_x[t]));
        const bool accepted = g.object_id[t] == g.object_id[c] && cos_angle >= cos_threshold;
        float du = g.coord_u_m[t] - g.coord_u_m[c], dv = g.coord_v_m[t] - g.coord_v_m[c], dn = 0.0f;
        if (g.sheared()) {
            dn = g.coord_n_m[t] - g.coord_n_m[c];
            du = mul_add(-g.shear_u[c], dn, du);
            dv = mul_add(-g.shear_v[c], dn, dv);
        }
        float exponent = g.anisotropic()
                             ? mul_add(du * du, -g.inv_two_sigma_sq[c], dv * dv * -g.inv_two_sigma_sq_v[c])
                             : mul_add(du, du, dv * dv) * -g.inv_two_sigma_sq[c];
        if (g.sheared()) exponent = mul_add(-(dn * dn), g.inv_two_sigma_sq_n[c], exponent);
        const float weight = !accepted ? 0.0f
                             : fused   ? gather_exp_nonpositive<true>(exponent)
                                       : gather_exp_nonpositive<false>(exponent);
        weight_sum += weight;
        sum = mul_add(weight, source[t], sum);
    }
    const float nx = g.normal_x[c], ny = g.normal_y[c], nz = g.normal_z[c];
    if (!(nx * nx + ny * ny + nz * nz >= cos_threshold && g.object_id[c] == g.object_id[c])) {
        sum += source[c];
        weight_sum += 1.0f;
    }
    return sum / weight_sum;
}

}  // namespace

TEST_CASE("Gather SIMD: the vertical pass and the separable gather give the scalar definition's bits",
          "[gather][simd]") {
    const aaf_test::UnpinnedInstructionSet every_target;  // the test walks Highway's targets itself
    // 29 x 23: a partial vector at each row's end for every lane count; radii
    // up to 7 reach past the top and bottom rows.
    const float cos_threshold = std::cos(25.0f * 3.14159265358979323846f / 180.0f);  // gather()'s default
    for (const bool anisotropic : {false, true})
        for (const bool sheared : {false, true})
            for (const bool symmetric : {false, true}) {
                const GatherGuides g = varied_guides(29, 23, sheared, anisotropic, true);
                const std::size_t n = std::size_t(g.width) * g.height;
                std::mt19937 rng(5);
                std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
                std::vector<float> source(n), vertical(n);
                for (float &v : source) v = unit(rng);
                // Per kind of instruction set: products rounded first, fused multiply-adds.
                std::vector<float> expected_vertical[2], expected[2];
                for (const bool fused : {false, true}) {
                    expected_vertical[fused].resize(n);
                    expected[fused].resize(n);
                    for (int y = 0; y < g.height; ++y)
                        for (int x = 0; x < g.width; ++x)
                            expected_vertical[fused][g.index(x, y)] =
                                reference_pass(g, source.data(), x, y, true, cos_threshold, symmetric, fused);
                    for (int y = 0; y < g.height; ++y)
                        for (int x = 0; x < g.width; ++x)
                            expected[fused][g.index(x, y)] =
                                reference_pass(g, expected_vertical[fused].data(), x, y, false, cos_threshold,
                                               symmetric, fused);
                }
                detail::GatherSweep sweep;
                sweep.guides = &g;
                sweep.cos_threshold = cos_threshold;
                sweep.symmetric_borders = symmetric;
                sweep.along_x = false;
                sweep.along_y = true;
                sweep.channels = 1;
                sweep.source[0] = source.data();
                sweep.output[0] = vertical.data();
                GatherSettings settings;
                settings.symmetric_borders = symmetric;
                for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
                    hwy::SetSupportedTargetsForTest(target);
                    INFO("target " << hwy::TargetName(target) << ", anisotropic " << anisotropic
                                   << ", sheared " << sheared << ", symmetric borders " << symmetric);
                    std::fill(vertical.begin(), vertical.end(), std::nanf(""));
                    for (int y = 0; y < g.height; ++y) detail::gather_row(sweep, y);
                    const bool fused = detail::gather_row_fuses();
                    CHECK(std::memcmp(vertical.data(), expected_vertical[fused].data(), n * sizeof(float)) ==
                          0);
                    // The whole separable gather, its output written over its source.
                    std::vector<float> image = source;
                    gather(g, settings, {plane_view<const float>(image.data(), g.width, g.height)},
                           {plane_view(image.data(), g.width, g.height)});
                    CHECK(std::memcmp(image.data(), expected[fused].data(), n * sizeof(float)) == 0);
                }
                hwy::SetSupportedTargetsForTest(0);
            }
}

TEST_CASE("Gather SIMD: column ranges and the tiled sweep give the bits of whole rows", "[gather][simd]") {
    // Wider than two strips, so the vertical sweep runs in tiles; 549 is not a
    // multiple of any lane count or of the strip, and 70 rows split into
    // several row blocks with the default strip and tile sizes.
    static_assert(549 > 2 * detail::kGatherStripPixels, "the image must be tiled");
    const float cos_threshold = std::cos(25.0f * 3.14159265358979323846f / 180.0f);
    for (const bool sheared : {false, true}) {
        const GatherGuides g = varied_guides(549, 70, sheared);
        const std::size_t n = std::size_t(g.width) * g.height;
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::vector<float> source_a(n), source_b(n);
        for (float &v : source_a) v = unit(rng);
        for (float &v : source_b) v = unit(rng);
        // Along y (the tiled case), along x and in 2D.
        for (const auto &[along_x, along_y] : {std::pair{false, true}, {true, false}, {true, true}}) {
            INFO("sheared " << sheared << ", along x " << along_x << ", along y " << along_y);
            detail::GatherSweep sweep;
            sweep.guides = &g;
            sweep.cos_threshold = cos_threshold;
            sweep.along_x = along_x;
            sweep.along_y = along_y;
            sweep.channels = 2;
            sweep.source[0] = source_a.data();
            sweep.source[1] = source_b.data();
            std::vector<float> expected_a(n), expected_b(n);
            sweep.output[0] = expected_a.data();
            sweep.output[1] = expected_b.data();
            for (int y = 0; y < g.height; ++y) detail::gather_row(sweep, y);

            std::vector<float> out_a(n, std::nanf("")), out_b(n, std::nanf(""));
            sweep.output[0] = out_a.data();
            sweep.output[1] = out_b.data();
            // Ranges that cut vectors and strips anywhere, one clamped at each end.
            for (int y = 0; y < g.height; ++y)
                for (const auto &[begin, end] : {std::pair{-5, 13}, {13, 300}, {300, 301}, {301, 600}})
                    detail::gather_row(sweep, y, begin, end);
            CHECK(std::memcmp(out_a.data(), expected_a.data(), n * sizeof(float)) == 0);
            CHECK(std::memcmp(out_b.data(), expected_b.data(), n * sizeof(float)) == 0);

            for (const int threads : {1, 2, 3}) {
                INFO(threads << " threads");
                std::fill(out_a.begin(), out_a.end(), std::nanf(""));
                std::fill(out_b.begin(), out_b.end(), std::nanf(""));
                run_with_threads(threads, [&] { detail::gather_rows_tiled(sweep); });
                CHECK(std::memcmp(out_a.data(), expected_a.data(), n * sizeof(float)) == 0);
                CHECK(std::memcmp(out_b.data(), expected_b.data(), n * sizeof(float)) == 0);
            }
        }
    }
}
