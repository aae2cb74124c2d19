// The tracer's backend seam (ray_queries.h): the Renderer and the AOV groups
// that trace rays of their own (isg, ratio, maaf6) make every ray query
// through the RayQueries they are given, in batches where they were batched.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/trace/render.h"
#include "aov_group.h"
#include "embree_scene.h"
#include "renderer.h"
#include "scene_file.h"

using namespace aaf;
using namespace aaf::trace;

namespace {

/// Counts the queries and their rays; answers them through `inner`.
class CountingRays final : public RayQueries {
  public:
    explicit CountingRays(const RayQueries &inner) : inner_(inner) {}
    void primary_hits(const Camera &camera, int y, int x_begin, int x_end, Hit *hits) const override {
        ++primary_calls;
        inner_.primary_hits(camera, y, x_begin, x_end, hits);
    }
    using RayQueries::occluded;
    void occluded(Vec3 origin, const Vec3 *directions, int count, float t_near, float t_far,
                  bool *blocked) const override {
        ++occluded_calls;
        occluded_rays += std::uint64_t(count);
        inner_.occluded(origin, directions, count, t_near, t_far, blocked);
    }
    Hit closest_hit(Vec3 origin, Vec3 direction, float t_near, float t_far) const override {
        ++closest_calls;
        return inner_.closest_hit(origin, direction, t_near, t_far);
    }
    mutable std::atomic<std::uint64_t> primary_calls{0}, occluded_calls{0}, occluded_rays{0},
        closest_calls{0};

  private:
    const RayQueries &inner_;
};

/// A backend with nothing in it: every ray misses, nothing is occluded.
class EmptyRays final : public RayQueries {
  public:
    void primary_hits(const Camera &, int, int x_begin, int x_end, Hit *hits) const override {
        for (int x = x_begin; x < x_end; ++x) hits[x - x_begin] = Hit{};
    }
    using RayQueries::occluded;
    void occluded(Vec3, const Vec3 *, int count, float, float, bool *blocked) const override {
        for (int k = 0; k < count; ++k) blocked[k] = false;
    }
    Hit closest_hit(Vec3, Vec3, float, float) const override { return {}; }
};

struct Fixture {
    RenderSettings settings;
    SceneDescription scene;
    Fixture() {
        settings.width = 24;
        settings.height = 18;
        settings.spp = 4;
        // MAAF's combined-effects scene: a thin lens, coloured walls (an
        // indirect bounce) and shadows.
        scene = load_scene_file(resolve_scene("room"), settings.width, settings.height);
    }
};

/// The isg, ratio and maaf6 groups' channels written with `renderer`'s
/// tracer, from `primaries` (the render's own).
AovSet write_groups(const Fixture &f, const Renderer &renderer, const std::vector<PrimaryHit> &primaries) {
    const std::vector<ShadowStats> stats(primaries.size());
    const RenderState state{f.scene,          f.scene.camera,    primaries, stats,          false,
                            f.settings.width, f.settings.height, &renderer, f.settings.spp, f.settings.seed};
    AovSet aovs(f.settings.width, f.settings.height);
    for (const auto &group : make_aov_accumulators(AovGroups{"isg", "ratio", "maaf6"}))
        group->write(state, aovs);
    return aovs;
}

/// Whether any pixel of `channel` is not `value`.
bool differs_from(const AovSet &aovs, const std::string &channel, float value) {
    const ConstPlaneView view = aovs.channel(channel);
    for (int y = 0; y < view.height; ++y)
        for (int x = 0; x < view.width; ++x)
            if (!(view(x, y) == value)) return true;
    return false;
}

}  // namespace

TEST_CASE("Tracer: a Renderer makes every ray query through its RayQueries, visibility rays in batches",
          "[trace][render]") {
    const Fixture f;
    const EmbreeScene embree(f.scene, false);
    const CountingRays counting(embree);
    const Renderer own(f.scene, f.settings);
    const Renderer through(f.scene, f.settings, counting);
    std::uint64_t pixels_traced = 0;
    for (int y = 0; y < f.settings.height; ++y) {
        std::vector<PrimaryHit> row(std::size_t(f.settings.width));
        through.trace_primaries(y, 0, f.settings.width, row.data());
        for (int x = 0; x < f.settings.width; ++x) {
            const PrimaryHit expected = own.trace_primary(x, y);
            const PrimaryHit &got = row[std::size_t(x)];
            REQUIRE(got.found == expected.found);
            CHECK((got.position == expected.position && got.normal == expected.normal));
            if (!got.found) continue;
            const std::uint64_t pixel = std::uint64_t(y) * f.settings.width + x;
            for (const bool distances : {false, true}) {
                ShadowStats a, b;
                own.trace_shadows(expected, x, y, pixel, 0, 64, distances, a, {});
                through.trace_shadows(got, x, y, pixel, 0, 64, distances, b, {});
                CHECK((a.unoccluded_weight_sum == b.unoccluded_weight_sum && a.d2_min_m == b.d2_min_m &&
                       a.d2_max_m == b.d2_max_m && a.radiance_sum[0] == b.radiance_sum[0]));
            }
            ++pixels_traced;
        }
    }
    REQUIRE(pixels_traced > 0);
    CHECK(counting.primary_calls == std::uint64_t(f.settings.height));  // a row's camera rays at once
    CHECK(counting.closest_calls > 0);  // occluder distances and the lens rays
    // The key light's 64 visibility rays a pixel go as one batch; the lens
    // rays' shading queries one by one.
    CHECK(counting.occluded_rays > 4 * counting.occluded_calls / 3);
}

TEST_CASE("Tracer: the isg, ratio and maaf6 groups trace every ray through the Renderer's RayQueries",
          "[trace][render]") {
    const Fixture f;
    const Renderer own(f.scene, f.settings);
    std::vector<PrimaryHit> primaries;
    for (int y = 0; y < f.settings.height; ++y)
        for (int x = 0; x < f.settings.width; ++x) primaries.push_back(own.trace_primary(x, y));

    // Through a counting backend over Embree: the same bytes as Embree alone.
    const EmbreeScene embree(f.scene, false);
    const CountingRays counting(embree);
    const Renderer counted(f.scene, f.settings, counting);
    const AovSet expected = write_groups(f, own, primaries), got = write_groups(f, counted, primaries);
    for (const std::string &name : expected.channel_names()) {
        INFO("channel " << name);
        const ConstPlaneView a = expected.channel(name), b = got.channel(name);
        bool same = true;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                same = same && std::memcmp(&a(x, y), &b(x, y), sizeof(float)) == 0;
        CHECK(same);
    }
    CHECK(counting.occluded_calls > 0);
    CHECK(counting.closest_calls > 0);

    // Through an empty backend: nothing blocks a shadow ray and no secondary
    // ray hits, where the scene itself has both. A group that asked Embree
    // behind the backend's back would still see the scene.
    REQUIRE(differs_from(expected, "isg.occluder_m", 0.0f));
    REQUIRE(differs_from(expected, "reflect.R", 0.0f));
    REQUIRE(differs_from(expected, "maaf6.indirect.R", 0.0f));
    const EmptyRays empty;
    const Renderer nothing(f.scene, f.settings, empty);
    const AovSet bare = write_groups(f, nothing, primaries);
    CHECK_FALSE(differs_from(bare, "isg.occluder_m", 0.0f));  // no occluder found
    CHECK_FALSE(differs_from(bare, "reflect.R", 0.0f));
    CHECK_FALSE(differs_from(bare, "maaf6.indirect.R", 0.0f));
    CHECK_FALSE(differs_from(bare, "maaf6.direct.R", 0.0f));  // the lens rays miss too
    const ConstPlaneView shadowed = bare.channel("ratio.S.R"), unshadowed = bare.channel("ratio.Un.R");
    bool equal = true;
    for (int y = 0; y < shadowed.height; ++y)
        for (int x = 0; x < shadowed.width; ++x) equal = equal && shadowed(x, y) == unshadowed(x, y);
    CHECK(equal);  // S_N == U_N bit for bit where no shadow ray is blocked
    const ConstPlaneView s0 = expected.channel("ratio.S.R"), u0 = expected.channel("ratio.Un.R");
    bool equal_with_scene = true;
    for (int y = 0; y < s0.height; ++y)
        for (int x = 0; x < s0.width; ++x) equal_with_scene = equal_with_scene && s0(x, y) == u0(x, y);
    CHECK_FALSE(equal_with_scene);
}
