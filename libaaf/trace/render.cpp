#include "aaf/trace/render.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/core/sampling_plan.h"
#include "renderer.h"
#include "scene_description.h"

namespace aaf::trace {

namespace {

constexpr int kTileSize = 16;

void validate(const RenderSettings &settings) {
    if (settings.width < 1 || settings.width > 16384 || settings.height < 1 || settings.height > 16384)
        throw Error("image size must lie in [1, 16384] pixels per side");
    if (settings.spp < 1 || settings.spp > (1 << 20)) throw Error("spp must lie in [1, 1048576]");
    if (settings.threads < 0) throw Error("threads must be >= 0");
    if (settings.adaptive) {
        if (settings.max_spp < settings.spp || settings.max_spp > (1 << 20))
            throw Error("max spp must lie in [spp, 1048576] for adaptive sampling");
        if (!(settings.adaptive_mu > 0)) throw Error("adaptive mu must be positive");
    }
}

/// Calls `body(x, y)` for every pixel, one 16x16 tile (clipped at the image's
/// edges) per task index over oneTBB. Each pixel is written by exactly one
/// call, so results do not depend on the schedule.
template <typename Body>
void for_each_pixel_tiled(int width, int height, const Body &body) {
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    const int tiles_y = (height + kTileSize - 1) / kTileSize;
    tbb::parallel_for(
        tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int> &tiles) {
            for (int tile = tiles.begin(); tile != tiles.end(); ++tile) {
                const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
                const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) body(x, y);
            }
        });
}

/// Writable views of the contract's channels for one role.
std::vector<PlaneView> add_role(AovSet &aovs, Role role) {
    std::vector<PlaneView> views;
    for (const std::string &name : role_info(role).channels) views.push_back(aovs.add_channel(name));
    return views;
}

/// Writes the AOVs of every pixel from its primary hit and shadow statistics.
void write_aovs(const std::vector<PrimaryHit> &primaries, const std::vector<ShadowStats> &stats,
                const LightPlane &light, AovSet &aovs) {
    const auto beauty = add_role(aovs, Role::Beauty);
    const auto visibility = add_role(aovs, Role::Visibility);
    const auto d1 = add_role(aovs, Role::D1);
    const auto d2_min = add_role(aovs, Role::D2Min);
    const auto d2_max = add_role(aovs, Role::D2Max);
    const auto position = add_role(aovs, Role::Position);
    const auto normal = add_role(aovs, Role::Normal);
    const auto object_id = add_role(aovs, Role::ObjectId);
    const auto spp = add_role(aovs, Role::SamplesPerPixel);
    const auto pixel_size = add_role(aovs, Role::PixelSize);
    const auto unshadowed = add_role(aovs, Role::Unshadowed);
    for (int y = 0; y < aovs.height(); ++y)
        for (int x = 0; x < aovs.width(); ++x) {
            const std::size_t i = std::size_t(y) * aovs.width() + x;
            const PrimaryHit &primary = primaries[i];
            visibility[0](x, y) = 1.0f;
            if (!primary.found) continue;  // background: zeros, visibility 1, no samples
            const float v = stats[i].visibility();
            const std::array<float, 3> r{primary.unshadowed.x, primary.unshadowed.y, primary.unshadowed.z};
            const std::array<float, 3> p{primary.position.x, primary.position.y, primary.position.z};
            const std::array<float, 3> n{primary.normal.x, primary.normal.y, primary.normal.z};
            for (int c = 0; c < 3; ++c) {
                beauty[c](x, y) = r[c] * v;  // AAF Eq. 1
                unshadowed[c](x, y) = r[c];
                position[c](x, y) = p[c];
                normal[c](x, y) = n[c];
            }
            visibility[0](x, y) = v;
            d1[0](x, y) = light.plane_distance_m(primary.position);
            if (stats[i].occluded_any()) {
                d2_min[0](x, y) = stats[i].d2_min_m;
                d2_max[0](x, y) = stats[i].d2_max_m;
            }
            object_id[0](x, y) = float(primary.mesh->object_id);
            spp[0](x, y) = float(stats[i].taken);
            pixel_size[0](x, y) = primary.pixel_size_m;
        }
}

}  // namespace

AovSet render_builtin(const std::string &scene_name, const RenderSettings &settings, RenderTimings *timings) {
    validate(settings);
    SceneDescription scene = make_builtin_scene(scene_name, settings.width, settings.height);
    if (settings.light_profile) scene.light.profile = *settings.light_profile;

    const std::size_t pixel_count = std::size_t(settings.width) * settings.height;
    std::vector<PrimaryHit> primaries(pixel_count);
    std::vector<ShadowStats> stats(pixel_count);
    const Renderer renderer(scene, settings);
    AovSet aovs(settings.width, settings.height);

    using Clock = std::chrono::steady_clock;
    auto seconds_since = [](Clock::time_point start) {
        return std::chrono::duration<double>(Clock::now() - start).count();
    };
    RenderTimings measured;
    // More threads than the machine runs gain nothing (and make oneTBB warn).
    tbb::task_arena arena(settings.threads == 0
                              ? tbb::task_arena::automatic
                              : std::min(settings.threads, tbb::info::default_concurrency()));
    arena.execute([&] {
        auto start = Clock::now();
        for_each_pixel_tiled(settings.width, settings.height, [&](int x, int y) {
            const std::size_t i = std::size_t(y) * settings.width + x;
            primaries[i] = renderer.trace_primary(x, y);
            if (primaries[i].found)
                renderer.trace_shadows(primaries[i], i, 0, std::uint32_t(settings.spp), stats[i]);
        });
        measured.first_pass_s = seconds_since(start);
        if (settings.adaptive) {
            start = Clock::now();
            // AAF Sec. 6: the per-pixel totals from the first pass's distances.
            AovSet first_pass(settings.width, settings.height);
            write_aovs(primaries, stats, scene.light, first_pass);
            write_light_attributes(scene.light, first_pass);
            AafParams aaf;
            aaf.mu = settings.adaptive_mu;
            SamplingPlanParams params;
            params.first_pass_spp = settings.spp;
            params.max_spp = settings.max_spp;
            const ChannelMap channels;
            const AovSet plan = plan_samples_aovs(first_pass, channels, aaf, params);
            const ConstPlaneView totals = plan.channel(channels.channel(Role::PlannedSpp));
            measured.plan_s = seconds_since(start);
            start = Clock::now();
            for_each_pixel_tiled(settings.width, settings.height, [&](int x, int y) {
                const std::size_t i = std::size_t(y) * settings.width + x;
                const int remaining = int(totals(x, y)) - settings.spp;
                if (primaries[i].found && remaining > 0)
                    renderer.trace_shadows(primaries[i], i, 1, std::uint32_t(remaining), stats[i]);
            });
            measured.second_pass_s = seconds_since(start);
        }
    });

    if (timings) *timings = measured;
    write_aovs(primaries, stats, scene.light, aovs);
    write_light_attributes(scene.light, aovs);
    aovs.attributes[attr::kScene] = scene_name;
    aovs.attributes[attr::kSeed] = int(settings.seed);
    aovs.attributes[attr::kSpp] = settings.spp;
    if (settings.adaptive) {
        aovs.attributes[attr::kAdaptiveMu] = settings.adaptive_mu;
        aovs.attributes[attr::kMaxSpp] = settings.max_spp;
    }
    aovs.attributes[attr::kCosineFalloff] = int(settings.cosine_falloff);
    return aovs;
}

}  // namespace aaf::trace
