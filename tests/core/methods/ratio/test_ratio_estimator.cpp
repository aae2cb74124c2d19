// The ratio estimator's filter side (Heitz, Hill, McGuire 2018) on synthetic
// AOV sets built in memory: the composition, the noise estimate (Eq. 29), the
// joint bilateral, per-light sums, temporal accumulation, determinism.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/ratio_layers.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/kernels/fixed_gaussian.h"
#include "aaf/core/methods/ratio/ratio_bilateral.h"
#include "aaf/core/methods/ratio/ratio_composition.h"
#include "aaf/core/methods/ratio/ratio_noise_estimate.h"
#include "aaf/core/util/error.h"

using namespace aaf;

namespace {

/// One pixel of one light: analytic U (RGB) and the stochastic S_N, U_N.
struct RatioPixel {
    float u[3] = {0, 0, 0}, s[3] = {0, 0, 0}, un[3] = {0, 0, 0};
};
using PixelFn = std::function<RatioPixel(int x, int y)>;

/// A flat floor (y = 0, normal +y) seen from above, 1 cm pixels, with the
/// ratio layers of each light from `lights` (one function per light), the
/// summed layers always, the per-light ones when there are several.
AovSet ratio_scene(int width, int height, const std::vector<PixelFn> &lights, float spacing_m = 0.01f) {
    AovSet aovs(width, height);
    const char *xyz[3] = {"X", "Y", "Z"};
    for (int c = 0; c < 3; ++c) {
        PlaneView p = aovs.add_channel(std::string("P.") + xyz[c]);
        PlaneView n = aovs.add_channel(std::string("N.") + xyz[c]);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                p(x, y) = c == 0 ? float(x) * spacing_m : c == 2 ? float(y) * spacing_m : 0.0f;
                n(x, y) = c == 1 ? 1.0f : 0.0f;
            }
    }
    std::fill_n(aovs.add_channel("pixel.size").data, aovs.pixel_count(), spacing_m);
    const char *rgb[3] = {"R", "G", "B"};
    auto add_layers = [&](const std::string &prefix, const std::vector<int> &which) {
        PlaneView u[3], s[3], un[3];
        for (int c = 0; c < 3; ++c) {
            u[c] = aovs.add_channel(prefix + "U." + rgb[c]);
            s[c] = aovs.add_channel(prefix + "S." + rgb[c]);
            un[c] = aovs.add_channel(prefix + "Un." + rgb[c]);
        }
        PlaneView s_y = aovs.add_channel(prefix + "S.Y"), un_y = aovs.add_channel(prefix + "Un.Y");
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (int light : which) {
                    const RatioPixel px = lights[std::size_t(light)](x, y);
                    for (int c = 0; c < 3; ++c) {
                        u[c](x, y) += px.u[c];
                        s[c](x, y) += px.s[c];
                        un[c](x, y) += px.un[c];
                    }
                    s_y(x, y) += 0.2126f * px.s[0] + 0.7152f * px.s[1] + 0.0722f * px.s[2];
                    un_y(x, y) += 0.2126f * px.un[0] + 0.7152f * px.un[1] + 0.0722f * px.un[2];
                }
    };
    std::vector<int> all;
    for (int i = 0; i < int(lights.size()); ++i) all.push_back(i);
    add_layers("ratio.", all);
    if (lights.size() > 1) {
        for (int i = 0; i < int(lights.size()); ++i) add_layers("ratio.L" + std::to_string(i) + ".", {i});
        aovs.attributes[attr::kRatioLights] = int(lights.size());
    }
    return aovs;
}

/// Deterministic per-pixel uniform numbers in [0, 1).
float hash01(int x, int y, int salt) {
    std::uint32_t h =
        std::uint32_t(x) * 73856093u ^ std::uint32_t(y) * 19349663u ^ std::uint32_t(salt) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return float(h >> 8) / 16777216.0f;
}

/// A textured U (so "sharp detail" is visible) and, at `spp` samples, a
/// stochastic S_N, U_N whose sample weights vary (1 to 3) and whose visibility
/// is `visible(x, y, sample)`.
PixelFn noisy_light(int spp, const std::function<bool(int, int, int)> &visible, int salt = 0) {
    return [=](int x, int y) {
        RatioPixel p;
        const float texture = ((x / 3 + y / 3) % 2) ? 0.8f : 0.3f;
        const float colour[3] = {1.0f, 0.7f, 0.4f};
        float s = 0, un = 0;
        for (int i = 0; i < spp; ++i) {
            const float weight = 1.0f + 2.0f * hash01(x, y, salt * 1000 + i);
            un += weight;
            if (visible(x, y, i)) s += weight;
        }
        for (int c = 0; c < 3; ++c) {
            p.u[c] = texture * colour[c] * 2.0f;
            p.s[c] = texture * colour[c] * s / float(spp);
            p.un[c] = texture * colour[c] * un / float(spp);
        }
        return p;
    };
}

ParameterSet ratio_parameters(std::initializer_list<std::pair<const char *, const char *>> values) {
    ParameterSet set = find_method("ratio").default_parameters();
    for (const auto &v : values) set.set(v.first, std::string(v.second));
    return set;
}

AovSet run_ratio(const AovSet &input, const ParameterSet &parameters, int threads = 0,
                 const AovSet *history = nullptr) {
    AovSet out;
    const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
    arena.execute(
        [&] { out = filter_aovs(find_method("ratio"), input, ChannelMap{}, parameters, {}, history); });
    return out;
}

float at(const AovSet &aovs, const std::string &name, int x, int y) {
    return aovs.channel(name)(x, y);
}

}  // namespace

TEST_CASE("Ratio: where every sample of every tap is unoccluded the result is U exactly (1 spp)", "[ratio]") {
    // Left of x = 20 a penumbra (random visibility), right of it fully lit.
    const int width = 64, height = 24;
    const PixelFn light =
        noisy_light(1, [](int x, int y, int i) { return x >= 20 || hash01(x, y, 7 + i) < 0.5f; });
    const AovSet input = ratio_scene(width, height, {light});
    for (const char *denoiser : {"bilateral", "gaussian"}) {
        INFO(denoiser);
        const AovSet out = run_ratio(input, ratio_parameters({{"denoiser", denoiser}}));
        // Beyond the widest reach from the penumbra (default noise lines 6 + box 1 + 3 x 8 px sigma
        // cap; 12 px gaussian).
        int exact = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 20 + 6 + 1 + 24 + 1; x < width; ++x) {
                for (const char *c : {"R", "G", "B"})
                    CHECK(at(out, std::string(c), x, y) == at(input, std::string("ratio.U.") + c, x, y));
                ++exact;
            }
        CHECK(exact > 0);
        // In the penumbra the result is shadowed: below U somewhere.
        bool darker = false;
        for (int y = 0; y < height; ++y) darker |= at(out, "G", 5, y) < at(input, "ratio.U.G", 5, y);
        CHECK(darker);
    }
}

TEST_CASE("Ratio: W stays in [0, 1] and the ratio result between 0 and U", "[ratio]") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    const int width = 32, height = 32;
    std::vector<float> s(width * height), u(width * height), w(width * height);
    for (std::size_t i = 0; i < s.size(); ++i) {
        u[i] = uniform(rng) < 0.2f ? 0.0f : uniform(rng) * 5.0f;
        s[i] = u[i] * (uniform(rng) < 0.3f ? 1.0f : uniform(rng));  // S_N <= U_N, bitwise equal at times
    }
    weighted_shadow(plane_view(s.data(), width, height), plane_view(u.data(), width, height),
                    plane_view(w.data(), width, height));
    for (float v : w) {
        CHECK(v >= 0.0f);
        CHECK(v <= 1.0f);
    }
    for (float a : {0.0f, 1e-30f, 0.5f, 3.0f})
        for (float b : {0.0f, 1e-30f, 0.5f, 3.0f, -1.0f}) {
            const float r = ratio_weight(a, b);
            CHECK(r >= 0.0f);
            CHECK(r <= 1.0f);
        }
    const PixelFn light =
        noisy_light(2, [](int x, int y, int i) { return hash01(x, y, i) < float(x) / 32.0f; });
    const AovSet input = ratio_scene(width, height, {light});
    const AovSet out = run_ratio(input, ratio_parameters({}));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (const char *c : {"R", "G", "B"}) {
                CHECK(at(out, c, x, y) >= 0.0f);
                CHECK(at(out, c, x, y) <= at(input, std::string("ratio.U.") + c, x, y));
            }
}

TEST_CASE("Ratio: S_N = U_N = 0 gives no NaN, for every estimator and denoiser", "[ratio]") {
    // A block where no sample reached the light (U_N = 0) though U > 0, and a
    // block where everything is 0; the rest in penumbra.
    const PixelFn light = [](int x, int y) {
        RatioPixel p = noisy_light(1, [](int x_, int y_, int i) { return hash01(x_, y_, i) < 0.5f; })(x, y);
        if (x < 12)
            for (int c = 0; c < 3; ++c) p.s[c] = p.un[c] = 0.0f;
        if (y < 6)
            for (int c = 0; c < 3; ++c) p.u[c] = p.s[c] = p.un[c] = 0.0f;
        return p;
    };
    const AovSet input = ratio_scene(32, 24, {light});
    for (const char *estimator : {"ratio", "stochastic", "control-variate"})
        for (const char *denoiser : {"bilateral", "gaussian"}) {
            INFO(estimator << " " << denoiser);
            const AovSet out =
                run_ratio(input, ratio_parameters({{"estimator", estimator}, {"denoiser", denoiser}}));
            for (const char *c : {"R", "G", "B"})
                for (int y = 0; y < 24; ++y)
                    for (int x = 0; x < 32; ++x) REQUIRE(std::isfinite(at(out, c, x, y)));
        }
    // Alone (no lit neighbour to borrow from): the pixel is shown unshadowed, W = 1.
    const AovSet out = run_ratio(input, ratio_parameters({{"denoiser", "gaussian"}, {"sigma", "0"}}));
    CHECK(at(out, "G", 3, 12) == at(input, "ratio.U.G", 3, 12));
    CHECK(at(out, "G", 3, 2) == 0.0f);
}

TEST_CASE(
    "Ratio: denoising before dividing converges to S/U as more pixels are averaged, after dividing does not "
    "(Eq. 26-27)",
    "[ratio]") {
    // Every pixel has the same BRDF, light and visibility: half the light's
    // directions are occluded and carry 3x the weight of the visible half, so
    // S / U = 1 / (1 + 3) = 0.25, while a 1-sample W_N is 1 with probability 0.5.
    const int width = 96, height = 96;
    const double reference = 0.25;
    std::vector<float> s(width * height), u(width * height), w(width * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const bool visible = hash01(x, y, 11) < 0.5f;
            const float weight = visible ? 1.0f : 3.0f;
            s[std::size_t(y) * width + x] = visible ? weight : 0.0f;
            u[std::size_t(y) * width + x] = weight;
            w[std::size_t(y) * width + x] = visible ? 1.0f : 0.0f;  // W_N = S_N / U_N
        }
    std::vector<double> before, after;
    for (float sigma : {1.0f, 4.0f, 16.0f}) {
        std::vector<float> ds(s.size()), du(s.size()), dw(s.size());
        fixed_gaussian_filter(plane_view(s.data(), width, height), sigma,
                              plane_view(ds.data(), width, height));
        fixed_gaussian_filter(plane_view(u.data(), width, height), sigma,
                              plane_view(du.data(), width, height));
        fixed_gaussian_filter(plane_view(w.data(), width, height), sigma,
                              plane_view(dw.data(), width, height));
        double e_before = 0, e_after = 0;
        int count = 0;
        for (int y = height / 4; y < 3 * height / 4; ++y)
            for (int x = width / 4; x < 3 * width / 4; ++x) {
                const std::size_t i = std::size_t(y) * width + x;
                e_before += std::pow(ratio_weight(ds[i], du[i]) - reference, 2);  // Eq. 27
                e_after += std::pow(dw[i] - reference, 2);                        // Eq. 26
                ++count;
            }
        before.push_back(std::sqrt(e_before / count));
        after.push_back(std::sqrt(e_after / count));
    }
    CHECK(before[1] < before[0]);
    CHECK(before[2] < before[1]);
    CHECK(before[2] < 0.02);
    for (double e : after) CHECK(e > 0.2);  // converges to E[W_N] = 0.5, not 0.25
}

TEST_CASE("Ratio noise estimate: 0 on a constant W, large on noise, a comb above a step (Sec. 4.2)",
          "[ratio]") {
    const int width = 40, height = 40;
    auto estimate = [&](const std::function<float(int, int)> &w_of) {
        std::vector<float> w(width * height), e(width * height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) w[std::size_t(y) * width + x] = w_of(x, y);
        ratio_noise_estimate(plane_view(static_cast<const float *>(w.data()), width, height), 3, 0,
                             plane_view(e.data(), width, height));
        return e;
    };
    for (float constant : {0.0f, 0.37f, 1.0f})
        for (float v : estimate([&](int, int) { return constant; })) CHECK(v == 0.0f);
    const std::vector<float> noise =
        estimate([](int x, int y) { return hash01(x, y, 5) < 0.5f ? 1.0f : 0.0f; });
    const std::vector<float> comb = estimate([](int x, int) { return float(x % 2); });
    const std::vector<float> step = estimate([](int x, int) { return x < 20 ? 0.0f : 1.0f; });
    const std::size_t centre = std::size_t(20) * width + 20;
    double noise_mean = 0;
    for (float v : noise) noise_mean += v / double(noise.size());
    CHECK(noise_mean > 0.5);
    CHECK(comb[centre] > 3.0f * step[centre]);  // a variance estimate would rank them equal
    CHECK(step[centre] > 0.0f);
    CHECK(step[centre] <= 2.0f / 5.0f);                // one unit step: at most 2 / (2 r - 1)
    CHECK(step[std::size_t(20) * width + 5] == 0.0f);  // away from the step
}

TEST_CASE("Ratio bilateral: taps across a depth discontinuity are rejected, on one plane they are not",
          "[ratio]") {
    // Left half: an umbra (S_N = 0) on a floor at y = 0; right half: lit
    // (S_N = U_N), either on the same floor or 0.5 m (50 footprints) above it.
    const int width = 40, height = 8;
    for (float step_m : {0.0f, 0.5f}) {
        INFO("right half raised by " << step_m << " m");
        AovSet aovs = ratio_scene(width, height, {[](int x, int) {
                                      RatioPixel p;
                                      for (int c = 0; c < 3; ++c) {
                                          p.u[c] = p.un[c] = 1.0f;
                                          p.s[c] = x < 20 ? 0.0f : 1.0f;
                                      }
                                      return p;
                                  }});
        PlaneView py = aovs.channel("P.Y");
        for (int y = 0; y < height; ++y)
            for (int x = 20; x < width; ++x) py(x, y) = step_m;
        RatioBilateralGuides guides;
        const char *xyz[3] = {"X", "Y", "Z"};
        for (int c = 0; c < 3; ++c) {
            guides.position[c] = aovs.channel(std::string("P.") + xyz[c]);
            guides.normal[c] = aovs.channel(std::string("N.") + xyz[c]);
        }
        guides.scale_m = aovs.channel("pixel.size");
        std::vector<float> sigma(width * height, 6.0f);
        const std::vector<ConstPlaneView> sources = {aovs.channel("ratio.S.G")};
        std::vector<float> out(width * height);
        ratio_bilateral(guides, plane_view(static_cast<const float *>(sigma.data()), width, height), {},
                        sources, {plane_view(out.data(), width, height)});
        const float leaked = out[std::size_t(4) * width + 19];  // last umbra pixel
        if (step_m > 0)
            CHECK(leaked < 1e-6f);
        else
            CHECK(leaked > 0.1f);
    }
}

TEST_CASE("Ratio: per-light results add up to the multi-light result", "[ratio]") {
    const int width = 48, height = 20;
    const PixelFn a = noisy_light(
        2, [](int x, int y, int i) { return hash01(x, y, 20 + i) < float(x) / 48.0f; }, 1);
    const PixelFn b = noisy_light(
        2, [](int x, int y, int i) { return hash01(x, y, 40 + i) < float(y) / 20.0f; }, 2);
    const AovSet both = ratio_scene(width, height, {a, b});
    const AovSet only_a = ratio_scene(width, height, {a}), only_b = ratio_scene(width, height, {b});
    for (const char *estimator : {"ratio", "stochastic", "control-variate"}) {
        INFO(estimator);
        const ParameterSet p = ratio_parameters({{"estimator", estimator}});
        const AovSet sum = run_ratio(both, p), ra = run_ratio(only_a, p), rb = run_ratio(only_b, p);
        const AovSet summed_layer =
            run_ratio(both, ratio_parameters({{"estimator", estimator}, {"summed", "true"}}));
        bool differs = false;
        for (const char *c : {"R", "G", "B"})
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    CHECK(at(sum, c, x, y) == at(ra, c, x, y) + at(rb, c, x, y));
                    differs |= at(summed_layer, c, x, y) != at(sum, c, x, y);
                }
        CHECK(differs);  // the per-light layers were used, not the summed one
    }
}

TEST_CASE("Ratio: a per-light layer the header promises but the file lacks is named in an input error",
          "[ratio]") {
    const PixelFn a = noisy_light(1, [](int, int, int) { return true; });
    AovSet input = ratio_scene(8, 8, {a, a});
    input.attributes[attr::kRatioLights] = 3;
    CHECK_THROWS_AS(run_ratio(input, ratio_parameters({})), InputError);
    CHECK_THROWS_WITH(run_ratio(input, ratio_parameters({})), Catch::Contains("ratio.L2.U.R"));
    CHECK(per_light_channel("ratio.S.R", 4) == "ratio.L4.S.R");
    CHECK(per_light_channel("ViewLayer.ratio.Un.Y", 0) == "ViewLayer.ratio.L0.Un.Y");
}

TEST_CASE("Ratio: --temporal lowers flicker on a static sequence and rejects a disocclusion", "[ratio]") {
    const int width = 40, height = 24;
    auto frame = [&](int f) {
        AovSet aovs = ratio_scene(width, height, {noisy_light(1, [f](int x, int y, int i) {
                                      return hash01(x, y, 100 * f + i) < float(x) / float(40);
                                  })});
        aovs.add_channel("motion.X");
        aovs.add_channel("motion.Y");
        return aovs;
    };
    const ParameterSet plain = ratio_parameters({}), temporal = ratio_parameters({{"temporal", "true"}});
    AovSet previous_plain, previous_temporal, history;
    double flicker_plain = 0, flicker_temporal = 0;
    for (int f = 0; f < 8; ++f) {
        const AovSet input = frame(f);
        const AovSet a = run_ratio(input, plain);
        const AovSet b = run_ratio(input, temporal, 0, f > 0 ? &history : nullptr);
        if (f >= 4) {  // after the history has built up
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    flicker_plain += std::pow(at(a, "G", x, y) - at(previous_plain, "G", x, y), 2);
                    flicker_temporal += std::pow(at(b, "G", x, y) - at(previous_temporal, "G", x, y), 2);
                }
        }
        previous_plain = a;
        previous_temporal = b;
        history = b;
    }
    CHECK(flicker_temporal < 0.5 * flicker_plain);

    // The history's surface moved off this frame's planes in the right half: there the current frame alone.
    AovSet moved = history;
    PlaneView py = moved.channel("P.Y");
    for (int y = 0; y < height; ++y)
        for (int x = 20; x < width; ++x) py(x, y) = 0.3f;
    const AovSet input = frame(9);
    const AovSet alone = run_ratio(input, plain), blended = run_ratio(input, temporal, 0, &moved);
    bool blended_left = false;
    for (int y = 0; y < height; ++y) {
        for (int x = 21; x < width; ++x) CHECK(at(blended, "G", x, y) == at(alone, "G", x, y));
        for (int x = 0; x < 19; ++x) blended_left |= at(blended, "G", x, y) != at(alone, "G", x, y);
    }
    CHECK(blended_left);
    // No motion layer: --temporal says what it needs.
    AovSet no_motion = ratio_scene(width, height, {noisy_light(1, [](int, int, int) { return true; })});
    CHECK_THROWS_WITH(run_ratio(no_motion, temporal, 0, &moved), Catch::Contains("motion"));
}

TEST_CASE("Ratio: 1 and 3 threads give identical bytes for every estimator and denoiser", "[ratio]") {
    const PixelFn a = noisy_light(
        2, [](int x, int y, int i) { return hash01(x, y, 60 + i) < float(x) / 40.0f; }, 3);
    const PixelFn b = noisy_light(
        1, [](int x, int y, int i) { return hash01(x, y, 80 + i) < 0.5f; }, 4);
    const AovSet input = ratio_scene(40, 30, {a, b});
    for (const char *estimator : {"ratio", "stochastic", "control-variate"})
        for (const char *denoiser : {"bilateral", "gaussian"}) {
            INFO(estimator << " " << denoiser);
            const ParameterSet p = ratio_parameters({{"estimator", estimator}, {"denoiser", denoiser}});
            const AovSet one = run_ratio(input, p, 1), three = run_ratio(input, p, 3);
            for (const char *c : {"R", "G", "B"})
                CHECK(std::memcmp(one.channel(c).data, three.channel(c).data,
                                  one.pixel_count() * sizeof(float)) == 0);
        }
    CHECK_THROWS_AS(run_ratio(input, ratio_parameters({{"estimator", "stochastic"}, {"grey", "true"}})),
                    Error);
}
