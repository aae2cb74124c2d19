#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/trace/render.h"
#include "aov_group.h"
#include "aov_groups/aov_groups.h"
#include "renderer.h"
#include "scene_file.h"

using namespace aaf;
using namespace aaf::trace;

namespace {

LightSample visible_sample(double weight) {
    LightSample sample;
    sample.weight = weight;
    return sample;
}

LightSample occluded_sample(double weight, float d2_m) {
    LightSample sample;
    sample.weight = weight;
    sample.visible = false;
    sample.d2_m = d2_m;
    sample.radiance = {0.25f, 0.5f, 1.0f};
    return sample;
}

/// A 2x1 image of grids: pixel 0 sees a receiver 1 m below the light's
/// centre, pixel 1 the background.
struct TwoPixels {
    SceneDescription scene = load_scene_file(resolve_scene("grids"), 2, 1);
    std::vector<PrimaryHit> primaries = std::vector<PrimaryHit>(2);
    std::vector<ShadowStats> stats = std::vector<ShadowStats>(2);

    TwoPixels() {
        primaries[0].found = true;
        primaries[0].position = scene.key_light().center + scene.key_light().normal;
        primaries[0].pixel_size_m = 0.01f;
    }
    RenderState state() const { return {scene, scene.camera, primaries, stats, false, 2, 1}; }
    AovSet write(const AovGroups &groups) const {
        AovSet aovs(2, 1);
        for (const auto &accumulator : make_aov_accumulators(groups)) accumulator->write(state(), aovs);
        return aovs;
    }
};

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

TEST_CASE("The shadow group writes the light-weighted visibility and occluder range of its samples",
          "[trace][groups]") {
    TwoPixels pixels;
    for (const LightSample &sample :
         {visible_sample(1), occluded_sample(1, 0.5f), visible_sample(2), occluded_sample(4, 0.25f)})
        pixels.stats[0].add(sample);
    const AovSet aovs = pixels.write({"shadow"});
    // AAF Eq. 1: V = (1 + 2) / (1 + 1 + 2 + 4), the unoccluded weight over all.
    CHECK(aovs.channel("shadow.V")(0, 0) == Approx(3.0 / 8.0));
    CHECK(aovs.channel("shadow.d2min")(0, 0) == 0.25f);
    CHECK(aovs.channel("shadow.d2max")(0, 0) == 0.5f);
    CHECK(aovs.channel("shadow.d1")(0, 0) == Approx(1.0f));
    CHECK(aovs.channel("pixel.spp")(0, 0) == 4.0f);
    CHECK(aovs.channel("pixel.size")(0, 0) == 0.01f);
    // The background: visibility 1, no distances, no samples.
    CHECK(aovs.channel("shadow.V")(1, 0) == 1.0f);
    CHECK(aovs.channel("shadow.d2max")(1, 0) == 0.0f);
    CHECK(aovs.channel("pixel.spp")(1, 0) == 0.0f);
    // The beauty comes first, then the group's channels in the contract's order.
    CHECK(aovs.channel_names().front() == "R");
}

TEST_CASE("Progress written and restored continues to the same sums as one render", "[trace][groups]") {
    TwoPixels pixels;
    const LightSample first[] = {occluded_sample(0.3, 0.7f), visible_sample(0.1), occluded_sample(0.2, 0.4f)};
    const LightSample later[] = {visible_sample(0.7), occluded_sample(0.9, 0.1f)};
    for (const LightSample &sample : first) pixels.stats[0].add(sample);
    pixels.stats[0].round_to_float();  // as after every round
    const AovSet partial = pixels.write({"shadow", "progress"});

    std::vector<ShadowStats> resumed(2);
    for (const auto &accumulator : make_aov_accumulators({"shadow", "progress"})) {
        for (const std::string &name : accumulator->resume_channels()) CHECK(partial.has_channel(name));
        accumulator->restore(partial, resumed);
    }
    for (const LightSample &sample : later) {
        pixels.stats[0].add(sample);
        resumed[0].add(sample);
    }
    const ShadowStats &a = pixels.stats[0], &b = resumed[0];
    CHECK(a.taken == b.taken);
    CHECK(same_bits(a.weight_sum, b.weight_sum));
    CHECK(same_bits(a.unoccluded_weight_sum, b.unoccluded_weight_sum));
    CHECK(a.d2_min_m == b.d2_min_m);
    CHECK(a.d2_max_m == b.d2_max_m);
    for (int c = 0; c < 3; ++c) CHECK(same_bits(a.radiance_sum[c], b.radiance_sum[c]));
}

namespace {

/// A group that wants every sample: counts them and sums their weights.
class CountingGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override { return group_info("counting", "none", roles()); }
    std::vector<Role> roles() const override { return {}; }
    bool wants_samples() const override { return true; }
    void add_sample(std::size_t pixel, const LightSample &sample) override {
        CHECK(pixel == 7);
        ++count;
        weight_sum += sample.weight;
        unoccluded_weight_sum += sample.visible ? sample.weight : 0.0;
        light_extent_ok &= std::abs(sample.y_u_m) <= 0.5f * light_width_m + 1e-5f;
    }
    void write(const RenderState &, AovSet &) const override {}

    float light_width_m = 0;
    int count = 0;
    double weight_sum = 0, unoccluded_weight_sum = 0;
    bool light_extent_ok = true;
};

}  // namespace

TEST_CASE("A group that wants samples sees every sample the shadow sums see", "[trace][groups]") {
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.cosine_falloff = true;  // weights other than 1
    const SceneDescription scene = load_scene_file(resolve_scene("grids"), settings.width, settings.height);
    const Renderer renderer(scene, settings);
    CountingGroup group;
    group.light_width_m = scene.key_light().width_m;
    std::vector<AovAccumulator *> listeners = {&group};
    // A ground pixel in a penumbra would do as well; any hit checks the sums.
    const PrimaryHit primary = renderer.trace_primary(32, 40);
    REQUIRE(primary.found);
    ShadowStats stats;
    renderer.trace_shadows(primary, 32, 40, 7, 0, 37, true, stats, listeners);
    CHECK(group.count == 37);
    CHECK(stats.taken == 37);
    CHECK(group.weight_sum == stats.weight_sum);
    CHECK(group.unoccluded_weight_sum == stats.unoccluded_weight_sum);
    CHECK(group.light_extent_ok);
}

TEST_CASE("The groups AAF reads follow from the roles it declares", "[trace][groups]") {
    const AovGroups aaf_groups = {"shadow", "position", "normal", "id", "unshadowed"};
    CHECK(aov_groups_writing(find_method("aaf").info().roles.required) == aaf_groups);
    CHECK(aov_groups_for_method("aaf") == aaf_groups);
    CHECK(parse_aov_groups("aaf") == aaf_groups);
    CHECK(parse_aov_groups("gaussian") == AovGroups{"shadow", "unshadowed"});
    CHECK(aov_groups_writing({}).empty());
}

TEST_CASE("The --aovs entry all is every registered group", "[trace][groups]") {
    CHECK(parse_aov_groups("all") == AovGroups::every());
    for (const AovGroupInfo &group : aov_group_table()) CHECK(parse_aov_groups("all").contains(group.name));
}

TEST_CASE("The --aovs entry GROUP renders what every method reading one of the group's own roles reads",
          "[trace][groups]") {
    std::vector<Role> shared;
    for (const RoleInfo &info : shared_roles()) shared.push_back(info.role);
    for (const AovGroupInfo &group : aov_group_table())
        for (const Method *method : methods()) {
            const std::vector<Role> &required = method->info().roles.required;
            const bool reads_own_role = std::any_of(group.roles.begin(), group.roles.end(), [&](Role role) {
                return std::find(shared.begin(), shared.end(), role) == shared.end() &&
                       std::find(required.begin(), required.end(), role) != required.end();
            });
            if (!reads_own_role) continue;
            INFO("--aovs " << group.name << " for " << method->info().name);
            CHECK(parse_aov_groups(group.name).contains(aov_groups_for_method(method->info().name)));
        }
    // isg's maps are read by three methods, none of them named isg.
    CHECK(parse_aov_groups("isg").contains(aov_groups_for_method("isg-shadow")));
    // A group of shared roles stays alone: AAF, MAAF and gaussian read the shadow group's.
    CHECK(parse_aov_groups("shadow") == AovGroups{"shadow"});
}

TEST_CASE("A group parameter's declared default is its settings member's initialiser", "[trace][groups]") {
    CHECK(maaf_group_parameters().defaults_read_back_differently().empty());
    CHECK(maaf6_group_parameters().defaults_read_back_differently().empty());
    // The registry declares the groups' parameters as their declarations do.
    CHECK(find_aov_group("maaf").parameters.front().default_value ==
          maaf_group_parameters().infos().front().default_value);
    CHECK(find_aov_group("maaf6").parameters.front().default_value ==
          maaf6_group_parameters().infos().front().default_value);
    // A value read and written back is the same text; one the group cannot use is refused.
    ParameterSet effects = maaf6_group_parameters().defaults();
    effects.set("maaf6_effects", std::string("indirect,shadows"));
    CHECK(maaf6_group_parameters().write(maaf6_group_parameters().read(effects)).text("maaf6_effects") ==
          "shadows,indirect");
    effects.set("maaf6_effects", std::string("bogus"));
    CHECK_THROWS_AS(maaf6_group_parameters().read(effects), Error);
}
