#include <catch2/catch.hpp>

#include <cstdint>

#include "aaf/trace/render.h"
#include "renderer.h"
#include "scene_file.h"

using namespace aaf;
using namespace aaf::trace;

TEST_CASE("Shadow rays in packets give the same samples as one at a time", "[trace][render]") {
    for (const bool falloff : {false, true}) {
        RenderSettings settings;
        settings.width = 40;
        settings.height = 30;
        settings.spp = 64;
        // With the falloff every sample has its own weight, so equal sums
        // mean the same samples were found visible, not just as many.
        settings.cosine_falloff = falloff;
        const SceneDescription scene =
            load_scene_file(resolve_scene("grids"), settings.width, settings.height);
        const Renderer single(scene, settings, ShadowRayGrouping::Single);
        const Renderer packets(scene, settings, ShadowRayGrouping::Packets);
        std::size_t differing = 0, penumbra_pixels = 0;
        for (int y = 0; y < settings.height; ++y)
            for (int x = 0; x < settings.width; ++x) {
                const PrimaryHit primary = single.trace_primary(x, y);
                if (!primary.found) continue;
                const std::uint64_t pixel = std::uint64_t(y) * settings.width + x;
                // Full batches of 64 (four packets) and a batch that ends in a partial packet.
                // Visibility only, and the closest hits' distances (d2 extremes).
                for (const std::uint32_t count : {64u, 37u})
                    for (const bool distances : {false, true}) {
                        ShadowStats one, grouped;
                        single.trace_shadows(primary, x, y, pixel, 1, count, distances, one, {});
                        packets.trace_shadows(primary, x, y, pixel, 1, count, distances, grouped, {});
                        differing += one.taken != grouped.taken || one.weight_sum != grouped.weight_sum ||
                                     one.unoccluded_weight_sum != grouped.unoccluded_weight_sum ||
                                     one.d2_min_m != grouped.d2_min_m || one.d2_max_m != grouped.d2_max_m;
                        penumbra_pixels +=
                            one.unoccluded_weight_sum > 0 && one.unoccluded_weight_sum < one.weight_sum;
                    }
            }
        INFO("falloff " << falloff);
        CHECK(differing == 0);
        CHECK(penumbra_pixels > 20);  // rays both blocked and not, within a packet
    }
}

TEST_CASE("ShadowStats::add_unit_weights gives add()'s sums", "[trace][render]") {
    const bool visible[] = {true, false, true, true, false, true, true};
    // Whole sums (counts at once), a sum past float's integers (after a
    // round_to_float) and sums that are not whole (the loop).
    for (const double start : {0.0, 37.0, 16777217.0, 0.5, 1e17 + 0.0}) {
        ShadowStats batched, one_by_one;
        batched.weight_sum = one_by_one.weight_sum = start;
        batched.unoccluded_weight_sum = one_by_one.unoccluded_weight_sum = start / 2;
        batched.add_unit_weights(visible, 7);
        for (const bool v : visible) {
            LightSample sample;
            sample.visible = v;
            one_by_one.add(sample);
        }
        INFO("start " << start);
        CHECK(batched.taken == one_by_one.taken);
        CHECK(batched.weight_sum == one_by_one.weight_sum);
        CHECK(batched.unoccluded_weight_sum == one_by_one.unoccluded_weight_sum);
        CHECK(batched.visibility() == one_by_one.visibility());
    }
}
