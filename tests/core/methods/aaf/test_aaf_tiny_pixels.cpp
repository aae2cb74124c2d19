#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/methods/aaf/aaf_filter.h"

using namespace aaf;

namespace {

/// AAF's inputs by their default channel names: a flat receiver 2 m under a
/// light; its left third under an occluder 1 m below the light, its middle
/// third under one touching it (d2 = d1: s2 = 0, so the pixel bandlimit alone
/// sets beta, ~pixel_size_m), the rest unoccluded; noisy visibility and
/// beauty; every pixel `pixel_size_m` wide.
AovSet flat_receiver(int width, int height, float pixel_size_m) {
    AovSet aovs(width, height);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> noise(0.0f, 1.0f);
    PlaneView visibility = aovs.add_channel("shadow.V");
    for (std::size_t i = 0; i < aovs.pixel_count(); ++i) visibility.data[i] = noise(rng);
    aovs.add_channel("shadow.d1", 2.0f);
    PlaneView d2_min = aovs.add_channel("shadow.d2min"), d2_max = aovs.add_channel("shadow.d2max");
    PlaneView px = aovs.add_channel("P.X"), pz = aovs.add_channel("P.Z");
    aovs.add_channel("P.Y", 0.0f);
    aovs.add_channel("N.X", 0.0f);
    aovs.add_channel("N.Y", 1.0f);
    aovs.add_channel("N.Z", 0.0f);
    aovs.add_channel("id.object", 1.0f);
    aovs.add_channel("pixel.size", pixel_size_m);
    aovs.add_channel("pixel.spp", 4.0f);
    for (const char *name : {"unshadowed.R", "unshadowed.G", "unshadowed.B"}) aovs.add_channel(name, 0.5f);
    for (const char *name : {"R", "G", "B"}) {
        PlaneView beauty = aovs.add_channel(name);
        for (std::size_t i = 0; i < aovs.pixel_count(); ++i) beauty.data[i] = 0.5f * visibility.data[i];
    }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            d2_min.data[i] = d2_max.data[i] = x < width / 3 ? 1.0f : x < 2 * width / 3 ? 2.0f : 0.0f;
            px.data[i] = float(x) * pixel_size_m;
            pz.data[i] = float(y) * pixel_size_m;
        }
    write_light_attributes(LightPlane::square({0, 2, 0}, {0, -1, 0}, 1.0f), aovs);
    return aovs;
}

std::size_t non_finite_values(const AovSet &aovs) {
    std::size_t count = 0;
    for (std::size_t c = 0; c < aovs.channel_names().size(); ++c)
        for (float v : aovs.plane(c)) count += !std::isfinite(v);
    return count;
}

}  // namespace

TEST_CASE("AAF output is finite everywhere for tiny, zero and denormal pixel sizes", "[aaf][filter]") {
    const float denormal = std::numeric_limits<float>::denorm_min() * 8;
    for (const float pixel_size_m : {1e-20f, 1e-30f, 1e-38f, denormal, 0.0f}) {
        for (const bool mu_from_spp : {false, true}) {
            CAPTURE(pixel_size_m, mu_from_spp);
            AafParams params;
            params.mu_from_spp = mu_from_spp;
            const AovSet out = aaf_filter_aovs(flat_receiver(12, 8, pixel_size_m), ChannelMap{}, params);
            for (const char *name : {"R", "G", "B", "aaf.V"}) REQUIRE(out.has_channel(name));
            CHECK(non_finite_values(out) == 0);
        }
    }
}
