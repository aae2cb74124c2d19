// MAAF for combined effects on a small render of `room`: each effect alone
// converges to its reference as spp grows, and MAAF and its axis-aligned
// baseline (--pairs 1) each bring the 16-spp render closer to its reference.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/methods/maaf6/maaf6_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/trace/render.h"

using namespace aaf;

namespace {

constexpr int kWidth = 48, kHeight = 36;

AovSet render_room(const std::string &effects, int spp, int seed, int width = kWidth, int height = kHeight) {
    trace::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.spp = spp;
    settings.seed = std::uint32_t(seed);
    settings.aovs = trace::parse_aov_groups("maaf6");
    settings.group_parameters.of("maaf6").set("maaf6_effects", effects);
    return trace::render_scene("room", settings);
}

/// RMS difference of the R, G, B channels.
double rmse(const AovSet &a, const AovSet &b) {
    double sum = 0;
    for (const char *name : {"R", "G", "B"}) {
        const ConstPlaneView va = a.channel(name), vb = b.channel(name);
        for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x)
                sum += double(va(x, y) - vb(x, y)) * double(va(x, y) - vb(x, y));
    }
    return std::sqrt(sum / (3.0 * a.width() * a.height()));
}

AovSet filtered(const AovSet &input, const char *pairs, double band_spp = 16) {
    const Method &method = find_method("maaf6");
    ParameterSet parameters = method.default_parameters();
    parameters.set("pairs", std::string(pairs));
    parameters.set("band_spp", band_spp);
    return filter_aovs(method, input, ChannelMap{}, parameters);
}

}  // namespace

TEST_CASE("maaf6: the group's channels follow the contract and the beauty is direct + indirect", "[maaf6]") {
    const AovSet render = render_room("all", 16, 1, 96, 72);
    for (Role role :
         {roles::Maaf6DirectSums, roles::Maaf6IndirectWeights, roles::Maaf6Wedge, roles::Maaf6Spp})
        for (const std::string &name : role_info(role).channels) REQUIRE(render.has_channel(name));
    const ConstPlaneView r = render.channel("R"), direct = render.channel("maaf6.direct.R"),
                         indirect = render.channel("maaf6.indirect.R"),
                         w00 = render.channel("maaf6.indirect.W_c0c0"),
                         v00 = render.channel("maaf6.direct.V_c0c0.R"), spp = render.channel("maaf6.spp");
    bool extra_seen = false;
    for (int y = 0; y < render.height(); ++y)
        for (int x = 0; x < render.width(); ++x) {
            REQUIRE(r(x, y) == Approx(direct(x, y) + indirect(x, y)));
            REQUIRE(w00(x, y) == spp(x, y));  // channel c0c0 counts the samples
            REQUIRE(v00(x, y) == Approx(direct(x, y) * spp(x, y)).epsilon(1e-4));
            extra_seen = extra_seen || spp(x, y) > 16;
        }
    CHECK(extra_seen);  // the room's table lies across the focal plane
}

TEST_CASE("maaf6: each effect alone converges to its reference as spp grows", "[maaf6]") {
    for (const char *effects : {"defocus", "shadows", "indirect", "all"}) {
        INFO(effects);
        const AovSet reference = render_room(effects, 512, 1000);
        double previous = 1e30;
        for (int spp : {4, 16, 64}) {
            const double error = rmse(render_room(effects, spp, 1), reference);
            CHECK(error < 0.75 * previous);  // about 1/sqrt(spp): halves per 4x
            previous = error;
        }
    }
}

TEST_CASE(
    "maaf6: with the default band_spp the filtered image of each effect alone converges to its reference",
    "[maaf6]") {
    // AAF Sec. 5.2's consistency: the bands (the pixel band too) widen as sqrt(spp / 16), so the
    // filter's bias shrinks as samples are added. With the paper's fixed bands (band_spp 0) it does
    // not, and this test fails: shadows alone go 0.0159, 0.0152, 0.0152 at 16, 64, 256 spp, all
    // effects 0.0179, 0.0143, 0.0135 (measured; with the default 0.0159, 0.0049, 0.0011 and 0.0179,
    // 0.0097, 0.0043).
    for (const char *effects : {"defocus", "shadows", "indirect", "all"}) {
        INFO(effects);
        const AovSet reference = render_room(effects, 1024, 1000);
        double previous = 1e30;
        for (int spp : {16, 64, 256}) {
            const double error = rmse(filtered(render_room(effects, spp, 1), "all"), reference);
            INFO(spp << " spp: " << error);
            CHECK(error < 0.8 * previous);
            previous = error;
        }
    }
}

TEST_CASE(
    "maaf6: the axis-aligned baseline (--pairs 1) reduces the error of indirect light alone and of all "
    "effects together at 16 spp, and a noise-free layer is left as it is",
    "[maaf6]") {
    // Shadows alone and defocus alone carry too little noise at this size to gain; they are checked
    // at 160x120 below.
    for (const char *effects : {"indirect", "all"}) {
        INFO(effects);
        const AovSet reference = render_room(effects, 256, 1000, 128, 96);
        const AovSet noisy = render_room(effects, 16, 2, 128, 96);
        const AovSet aaf = filtered(noisy, "1");
        CHECK(rmse(aaf, reference) < 0.8 * rmse(noisy, reference));
        if (std::string(effects) != "indirect") continue;
        // Pinhole and the light's centre: the direct layer has no noise and no wedge, and stays exact.
        for (const char *name : {"maaf6.direct.R", "maaf6.direct.G", "maaf6.direct.B"}) {
            const ConstPlaneView in = noisy.channel(name), out = aaf.channel(name);
            for (int y = 0; y < noisy.height(); ++y)
                for (int x = 0; x < noisy.width(); ++x) REQUIRE(out(x, y) == in(x, y));
        }
    }
}

TEST_CASE("maaf6: the render and both filters give the same bytes for any thread count", "[maaf6]") {
    auto render = [](int threads) {
        trace::RenderSettings settings;
        settings.width = 32;
        settings.height = 24;
        settings.spp = 8;
        settings.threads = threads;
        settings.aovs = trace::parse_aov_groups("maaf6");
        return trace::render_scene("room", settings);
    };
    const AovSet one = render(1), three = render(3);
    REQUIRE(one.channel_names() == three.channel_names());
    for (const std::string &name : one.channel_names()) {
        INFO(name);
        REQUIRE(one.plane(one.index_of(name)) == three.plane(three.index_of(name)));
    }
    const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
    for (const char *pairs : {"all", "1"}) {
        AovSet a, b;
        tbb::task_arena(1).execute([&] { a = filtered(one, pairs); });
        tbb::task_arena(3).execute([&] { b = filtered(three, pairs); });
        for (const char *name : {"R", "G", "B"})
            REQUIRE(a.plane(a.index_of(name)) == b.plane(b.index_of(name)));
    }
}

TEST_CASE("maaf6: a band header attribute that is infinite, negative or NaN is an input error naming it",
          "[maaf6]") {
    const AovSet render = render_room("all", 4, 1, 16, 12);
    const float bad[] = {INFINITY, -1.0f, NAN};
    for (const char *name : {attr::kMaaf6OmegaLens, attr::kMaaf6OmegaDirect, attr::kMaaf6OmegaIndirect})
        for (float value : bad) {
            INFO(name << " = " << value);
            AovSet broken = render;
            broken.attributes[name] = value;
            try {
                (void)filtered(broken, "all");
                FAIL("no error");
            } catch (const InputError &e) {
                CHECK(std::string(e.what()).find(name) != std::string::npos);
            }
        }
}

TEST_CASE(
    "maaf6: `aaf filter aaf` and `aaf filter maaf` on a combined render run maaf6 --pairs 1 and maaf6, "
    "and refuse their own options",
    "[maaf6]") {
    const AovSet render = render_room("all", 8, 1, 32, 24);
    const auto same = [](const AovSet &a, const AovSet &b) {
        REQUIRE(a.channel_names() == b.channel_names());
        for (const std::string &name : a.channel_names()) {
            INFO(name);
            REQUIRE(a.plane(a.index_of(name)) == b.plane(b.index_of(name)));
        }
    };
    const Method &aaf = find_method("aaf"), &maaf = find_method("maaf");
    // The two delegates' outputs differ on this render, so each equality below says which one ran.
    const AovSet one_pair = filtered(render, "1"), all_pairs = filtered(render, "all");
    REQUIRE(one_pair.plane(one_pair.index_of("R")) != all_pairs.plane(all_pairs.index_of("R")));
    same(filter_aovs(aaf, render, ChannelMap{}, aaf.default_parameters()), filtered(render, "1"));
    same(filter_aovs(maaf, render, ChannelMap{}, maaf.default_parameters()), filtered(render, "all"));

    const MethodChoice choice = choose_method(aaf, aaf.default_parameters(), render, ChannelMap{});
    CHECK(choice.method == &find_method("maaf6"));
    CHECK(choice.parameters.text("pairs") == "1");
    CHECK(choice.note.find("aaf filter maaf6 --pairs 1") != std::string::npos);

    // An AAF option that is not the default would be lost: an error naming it and where to go.
    ParameterSet mu = aaf.default_parameters();
    mu.set("mu", 3.0);
    CHECK_THROWS_WITH(filter_aovs(aaf, render, ChannelMap{}, mu),
                      Catch::Contains("--mu") && Catch::Contains("aaf filter maaf6 --pairs 1"));

    // Without the whole maaf6 layer nothing is handed over: AAF names its own missing input.
    AovSet partial = render;
    (void)partial.take_channel("maaf6.spp");
    CHECK(choose_method(aaf, aaf.default_parameters(), partial, ChannelMap{}).method == &aaf);
    CHECK(choose_method(aaf, aaf.default_parameters(), partial, ChannelMap{}).note.empty());
    CHECK_THROWS_AS(filter_aovs(aaf, partial, ChannelMap{}, aaf.default_parameters()), InputError);
    CHECK_THROWS_WITH(filter_aovs(aaf, partial, ChannelMap{}, aaf.default_parameters()),
                      Catch::Contains("AAF") && Catch::Contains("unshadowed"));
}

TEST_CASE("maaf6: shadows alone and defocus alone are brought closer to their references at 160x120, 16 spp",
          "[maaf6]") {
    // Issue 15's "each effect alone reduces RMSE" for the two effects whose noise is small at 48x36
    // (indirect light alone is the case above). Measured by scripts/maaf6_per_effect.sh 160 120 256 16:
    // shadows 0.00870 -> 0.00802 (N = 1) / 0.00804 (N = 3), defocus 0.00612 -> 0.00576 / 0.00577.
    // A filter that did nothing would give the unfiltered error; one that blurs more, a larger one.
    for (const char *effects : {"shadows", "defocus"}) {
        INFO(effects);
        const AovSet reference = render_room(effects, 256, 1000, 160, 120);
        const AovSet noisy = render_room(effects, 16, 1, 160, 120);
        const double unfiltered = rmse(noisy, reference);
        for (const char *pairs : {"1", "all"}) {
            INFO("pairs " << pairs);
            CHECK(rmse(filtered(noisy, pairs), reference) < 0.97 * unfiltered);
        }
    }
}

TEST_CASE("maaf6: the vector filter is the scalar double-precision filter to float rounding", "[maaf6]") {
    // The default (--filter vector: each tap for a vector of centres, in float with polynomial exp and
    // sin/cos) against the one-centre-at-a-time double loop it replaced (--filter scalar, the same bits as
    // before), on every effect together and with a narrower k (more pixels keep the partition), N = 3
    // and N = 1. Measured: largest difference 4e-6 on values up to 2 (room, 320x240, 16 spp).
    const AovSet render = render_room("all", 16, 3, 96, 72);
    const Method &method = find_method("maaf6");
    for (const double k : {1.0, 0.5})
        for (const char *pairs : {"all", "1"}) {
            ParameterSet parameters = method.default_parameters();
            parameters.set("k", k);
            parameters.set("pairs", std::string(pairs));
            const AovSet vector = filter_aovs(method, render, ChannelMap{}, parameters);
            parameters.set("filter", std::string("scalar"));
            const AovSet scalar = filter_aovs(method, render, ChannelMap{}, parameters);
            double worst = 0, largest = 0;
            for (const char *name : {"R", "G", "B", "maaf6.direct.R", "maaf6.indirect.G"}) {
                const ConstPlaneView v = vector.channel(name), s = scalar.channel(name);
                for (int y = 0; y < render.height(); ++y)
                    for (int x = 0; x < render.width(); ++x) {
                        worst = std::max(worst, std::abs(double(v(x, y)) - double(s(x, y))) /
                                                    (1.0 + std::abs(double(s(x, y)))));
                        largest = std::max(largest, std::abs(double(s(x, y))));
                    }
            }
            INFO("k " << k << ", pairs " << pairs << ": largest difference relative to 1 + |value| " << worst
                      << " (values up to " << largest << ")");
            CHECK(largest > 0.1);
            CHECK(worst < 2e-5);
        }
}
