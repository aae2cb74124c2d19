#include "aaf/trace/render.h"

#include <pmmintrin.h>  // flush-to-zero and denormals-are-zero
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <type_traits>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/core/sampling_plan.h"
#include "renderer.h"
#include "scene_description.h"
#include "scene_file.h"
#include "scene_hash.h"

namespace aaf::trace {

namespace {

constexpr int kTileSize = 16;
/// Random-number pass of the adaptive second pass, apart from the rounds' passes.
constexpr std::uint32_t kAdaptiveSecondPass = 1u << 30;

void validate(const RenderSettings &settings) {
    if (settings.width < 1 || settings.width > 16384 || settings.height < 1 || settings.height > 16384)
        throw Error("image size must lie in [1, 16384] pixels per side");
    if (settings.spp < 1 || settings.spp > (1 << 20)) throw Error("spp must lie in [1, 1048576]");
    if (settings.threads < 0 || settings.threads > 1024)
        throw Error("threads must lie in [0, 1024] (0 = all cores)");
    if (!std::isfinite(settings.frame)) throw Error("frame must be finite");
    if (settings.adaptive) {
        if (settings.max_spp < settings.spp || settings.max_spp > (1 << 20))
            throw Error("max spp must lie in [spp, 1048576] for adaptive sampling");
        if (!(settings.adaptive_mu > 0)) throw Error("adaptive mu must be positive");
        if (settings.resume) throw Error("an adaptive render cannot be resumed");
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
            // Denormals only slow the traversal down; flush them on every worker.
            _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
            _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
            for (int tile = tiles.begin(); tile != tiles.end(); ++tile) {
                const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
                const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) body(x, y);
            }
        });
}

/// Writable views of the contract's channels for one role, stored at `precision`.
std::vector<PlaneView> add_role(AovSet &aovs, Role role, Precision precision = Precision::Float) {
    std::vector<PlaneView> views;
    for (const std::string &name : role_info(role).channels) {
        views.push_back(aovs.add_channel(name));
        aovs.set_precision(name, precision);
    }
    return views;
}

/// Everything the AOV groups are written from.
struct Frame {
    const SceneDescription &scene;
    const Camera &previous_camera;  ///< for motion vectors
    const std::vector<PrimaryHit> &primaries;
    const std::vector<ShadowStats> &stats;
    bool separate_radiance;
};

void set3(const std::vector<PlaneView> &views, int x, int y, Vec3 v) {
    views[0](x, y) = v.x;
    views[1](x, y) = v.y;
    views[2](x, y) = v.z;
}

/// Writes the beauty and the selected groups, one block per group.
void write_aovs(const Frame &frame, unsigned groups, AovSet &aovs) {
    const int width = aovs.width(), height = aovs.height();
    auto for_each = [&](const auto &body) {
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * width + x;
                body(x, y, frame.primaries[i], frame.stats[i]);
            }
    };
    const bool thin_lens = frame.scene.camera.is_thin_lens();
    auto separate = [&](const ShadowStats &s) {
        const double n = s.taken > 0 ? double(s.taken) : 1.0;
        return Vec3{float(s.radiance_sum[0] / n), float(s.radiance_sum[1] / n), float(s.radiance_sum[2] / n)};
    };

    const auto beauty = add_role(aovs, Role::Beauty);
    for_each([&](int x, int y, const PrimaryHit &primary, const ShadowStats &s) {
        if (thin_lens)
            set3(beauty, x, y, separate(s));  // defocused: the lens rays' radiance
        else if (primary.found)               // AAF Eq. 1, plus the other lights
            set3(beauty, x, y,
                 primary.unshadowed * s.visibility() + (frame.separate_radiance ? separate(s) : Vec3{}));
    });

    if (groups & kAovShadow) {
        const LightPlane &light = frame.scene.key_light();
        const auto visibility = add_role(aovs, Role::Visibility);
        const auto d1 = add_role(aovs, Role::D1);
        const auto d2_min = add_role(aovs, Role::D2Min);
        const auto d2_max = add_role(aovs, Role::D2Max);
        const auto spp = add_role(aovs, Role::SamplesPerPixel);
        const auto pixel_size = add_role(aovs, Role::PixelSize);
        for_each([&](int x, int y, const PrimaryHit &primary, const ShadowStats &s) {
            visibility[0](x, y) = 1.0f;  // background: visibility 1, distances 0
            spp[0](x, y) = float(s.taken);
            if (!primary.found) return;
            visibility[0](x, y) = s.visibility();
            d1[0](x, y) = light.plane_distance_m(primary.position);
            if (s.occluded_any()) {
                d2_min[0](x, y) = s.d2_min_m;
                d2_max[0](x, y) = s.d2_max_m;
            }
            pixel_size[0](x, y) = primary.pixel_size_m;
        });
        if (frame.separate_radiance && !thin_lens) {
            const auto other = add_role(aovs, Role::OtherLights);
            for_each([&](int x, int y, const PrimaryHit &, const ShadowStats &s) {
                set3(other, x, y, separate(s));
            });
        }
    }
    // Groups that copy one value of the primary hit per pixel (0 where nothing was hit).
    auto write_hit = [&](Role role, Precision precision, const auto &value) {
        const auto views = add_role(aovs, role, precision);
        for_each([&](int x, int y, const PrimaryHit &p, const ShadowStats &) {
            if (!p.found) return;
            const auto v = value(p);
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, Vec3>)
                set3(views, x, y, v);
            else
                views[0](x, y) = float(v);
        });
    };
    if (groups & kAovPosition)
        write_hit(Role::Position, Precision::Float, [](const PrimaryHit &p) { return p.position; });
    if (groups & kAovNormal)
        write_hit(Role::Normal, Precision::Float, [](const PrimaryHit &p) { return p.normal; });
    if (groups & kAovObjectId)
        write_hit(Role::ObjectId, Precision::Float, [](const PrimaryHit &p) { return p.mesh->object_id; });
    if (groups & kAovUnshadowed)
        write_hit(Role::Unshadowed, Precision::Float, [](const PrimaryHit &p) { return p.unshadowed; });
    if (groups & kAovDepth)
        write_hit(Role::Depth, Precision::Float, [](const PrimaryHit &p) { return p.depth_m; });
    // Reflectances in [0, 1] and motion of a few pixels need no more than half's
    // 11 bits; the beauty stays float, since references are compared to 1e-4.
    if (groups & kAovAlbedo)
        write_hit(Role::Albedo, Precision::Half, [](const PrimaryHit &p) { return p.mesh->material.albedo; });
    if (groups & kAovMotion) {
        // Geometry is static; only the camera moves the surface point on screen.
        const auto motion = add_role(aovs, Role::Motion, Precision::Half);
        // Both positions are projected the same way, so a still camera gives exactly 0.
        for_each([&](int x, int y, const PrimaryHit &p, const ShadowStats &) {
            float now_x, now_y, before_x, before_y;
            if (!p.found || !frame.scene.camera.raster_of(p.position, now_x, now_y) ||
                !frame.previous_camera.raster_of(p.position, before_x, before_y))
                return;
            motion[0](x, y) = now_x - before_x;
            motion[1](x, y) = now_y - before_y;
        });
    }
    if (groups & kAovProgress) {
        const auto weight = add_role(aovs, Role::ProgressWeight);
        const auto unoccluded = add_role(aovs, Role::ProgressUnoccluded);
        const auto radiance = add_role(aovs, Role::ProgressRadiance);
        for_each([&](int x, int y, const PrimaryHit &, const ShadowStats &s) {
            weight[0](x, y) = float(s.weight_sum);
            unoccluded[0](x, y) = float(s.unoccluded_weight_sum);
            set3(radiance, x, y,
                 {float(s.radiance_sum[0]), float(s.radiance_sum[1]), float(s.radiance_sum[2])});
        });
    }
}

void write_attributes(const SceneDescription &scene, const RenderSettings &settings, int spp_done,
                      AovSet &aovs) {
    write_light_attributes(scene.key_light(), aovs);
    aovs.attributes[attr::kScene] = scene.name;
    aovs.attributes[attr::kSceneFile] = scene.source;
    aovs.attributes[attr::kSceneHash] = hash_to_hex(scene_hash(scene, settings));
    aovs.attributes[attr::kLightCount] = int(scene.lights.size());
    aovs.attributes[attr::kApertureRadius] = scene.camera.aperture_radius_m;
    aovs.attributes[attr::kSeed] = int(settings.seed);
    aovs.attributes[attr::kSpp] = settings.spp;
    aovs.attributes[attr::kSppDone] = spp_done;
    aovs.attributes[attr::kFrame] = float(settings.frame);
    if (settings.adaptive) {
        aovs.attributes[attr::kAdaptiveMu] = settings.adaptive_mu;
        aovs.attributes[attr::kMaxSpp] = settings.max_spp;
    }
    aovs.attributes[attr::kCosineFalloff] = int(settings.cosine_falloff);
}

/// Restores the per-pixel sums of a partial render and returns its samples
/// per pixel; throws aaf::InputError when it is not a partial render of the
/// same scene, seed, size, frame and light, or when the scene's content
/// changed since (scene_hash.h).
int restore_progress(const AovSet &partial, const SceneDescription &scene, const RenderSettings &settings,
                     std::vector<ShadowStats> &stats) {
    auto fail = [&](const std::string &problem) {
        const std::string &source = settings.resume_source;
        throw InputError((source.empty() ? "" : source + ": ") + "cannot resume: " + problem);
    };
    auto attribute = [&](const char *name) -> const AttributeValue & {
        auto it = partial.attributes.find(name);
        if (it == partial.attributes.end()) fail(std::string("missing header attribute '") + name + "'");
        return it->second;
    };
    auto expect = [&](const char *name, const AttributeValue &value) {
        if (!(attribute(name) == value))
            fail(std::string("header attribute '") + name + "' differs from this render's");
    };
    if (partial.width() != settings.width || partial.height() != settings.height)
        fail("its size is " + std::to_string(partial.width()) + "x" + std::to_string(partial.height()));
    expect(attr::kScene, scene.name);
    expect(attr::kSeed, int(settings.seed));
    expect(attr::kFrame, float(settings.frame));
    expect(attr::kCosineFalloff, int(settings.cosine_falloff));
    expect(attr::kLightKind, std::string(to_string(scene.key_light().profile)));
    if (partial.attributes.count(attr::kAdaptiveMu)) fail("it is an adaptive render");
    // Checked after the specific attributes above, whose messages say more.
    if (!(attribute(attr::kSceneHash) == AttributeValue(hash_to_hex(scene_hash(scene, settings)))))
        fail("the scene changed since it was rendered (header attribute 'aaf:scene_hash' differs)");
    const int *done = std::get_if<int>(&attribute(attr::kSppDone));
    if (!done) fail("header attribute 'aaf:spp_done' is not an int");
    if (*done > settings.spp) fail("it already has " + std::to_string(*done) + " spp, more than --spp");
    for (Role role : {Role::SamplesPerPixel, Role::D2Min, Role::D2Max, Role::ProgressWeight,
                      Role::ProgressUnoccluded, Role::ProgressRadiance})
        for (const std::string &name : role_info(role).channels)
            if (!partial.has_channel(name))
                fail("it has no channel '" + name + "' (render with --aovs including progress)");
    auto plane = [&](Role role, std::size_t c = 0) { return partial.channel(role_info(role).channels[c]); };
    const auto taken = plane(Role::SamplesPerPixel), d2_min = plane(Role::D2Min), d2_max = plane(Role::D2Max),
               weight = plane(Role::ProgressWeight), unoccluded = plane(Role::ProgressUnoccluded);
    const ConstPlaneView radiance[3] = {plane(Role::ProgressRadiance, 0), plane(Role::ProgressRadiance, 1),
                                        plane(Role::ProgressRadiance, 2)};
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x) {
            ShadowStats &s = stats[std::size_t(y) * settings.width + x];
            s.taken = std::uint32_t(taken(x, y));
            s.weight_sum = weight(x, y);
            s.unoccluded_weight_sum = unoccluded(x, y);
            if (d2_max(x, y) > 0) {
                s.d2_min_m = d2_min(x, y);
                s.d2_max_m = d2_max(x, y);
            }
            for (int c = 0; c < 3; ++c) s.radiance_sum[c] = radiance[c](x, y);
        }
    return *done;
}

}  // namespace

const std::vector<AovGroupInfo> &aov_group_table() {
    static const std::vector<AovGroupInfo> table = {
        {kAovShadow, "shadow",
         "shadow.V, shadow.d1, shadow.d2min, shadow.d2max, pixel.spp, pixel.size (and otherlights.R/G/B with "
         "several lights)"},
        {kAovPosition, "position", "P.X, P.Y, P.Z"},
        {kAovNormal, "normal", "N.X, N.Y, N.Z"},
        {kAovObjectId, "id", "id.object"},
        {kAovUnshadowed, "unshadowed", "unshadowed.R, unshadowed.G, unshadowed.B"},
        {kAovDepth, "depth", "Z"},
        {kAovAlbedo, "albedo", "albedo.R, albedo.G, albedo.B"},
        {kAovMotion, "motion", "motion.X, motion.Y"},
        {kAovProgress, "progress",
         "progress.weight, progress.unoccluded, progress.radiance.R/G/B (for --resume)"},
    };
    return table;
}

unsigned parse_aov_groups(const std::string &list) {
    unsigned groups = 0;
    std::stringstream items(list);
    for (std::string item; std::getline(items, item, ',');) {
        if (item == "aaf") {
            groups |= kAovsForAaf;
            continue;
        }
        if (item == "all") {
            groups |= kAovsAll;
            continue;
        }
        bool found = false;
        for (const AovGroupInfo &info : aov_group_table())
            if (item == info.name) {
                groups |= info.group;
                found = true;
            }
        if (!found) {
            std::string known = "aaf, all";
            for (const AovGroupInfo &info : aov_group_table()) known += std::string(", ") + info.name;
            throw Error("unknown AOV group '" + item + "' (known: " + known + ")");
        }
    }
    return groups;
}

AovSet render_scene(const std::string &scene_name, const RenderSettings &settings, RenderTimings *timings) {
    validate(settings);
    SceneDescription scene = load_scene_file(resolve_scene(scene_name), settings.width, settings.height);
    scene.set_frame(settings.frame);
    if (settings.light_profile)
        for (SceneLight &light : scene.lights) light.plane.profile = *settings.light_profile;
    const Camera previous_camera = scene.camera_at(settings.frame - 1);

    unsigned groups = settings.aovs;
    // A reference (a round or more) can always be resumed to more samples.
    if (!settings.adaptive && (settings.spp >= kSamplesPerRound || settings.resume)) groups |= kAovProgress;
    // Resuming needs the spp and occluder distances beside the sums.
    if (groups & kAovProgress) groups |= kAovShadow;

    const std::size_t pixel_count = std::size_t(settings.width) * settings.height;
    std::vector<PrimaryHit> primaries(pixel_count);
    std::vector<ShadowStats> stats(pixel_count);
    const Renderer renderer(scene, settings);
    const bool separate = renderer.has_separate_radiance();
    const bool thin_lens = scene.camera.is_thin_lens();
    const Frame frame{scene, previous_camera, primaries, stats, separate};
    int spp_done = settings.resume ? restore_progress(*settings.resume, scene, settings, stats) : 0;

    auto render_so_far = [&](int done) {
        AovSet aovs(settings.width, settings.height);
        write_aovs(frame, groups, aovs);
        write_attributes(scene, settings, done, aovs);
        return aovs;
    };

    using Clock = std::chrono::steady_clock;
    auto seconds_since = [](Clock::time_point start) {
        return std::chrono::duration<double>(Clock::now() - start).count();
    };
    RenderTimings measured;
    // oneTBB caps its workers at the hardware's threads (and warns) unless the
    // process-wide limit is raised: raise it for this render, so `threads`
    // really run (a 1-core machine still checks 1 vs 2 threads).
    std::optional<tbb::global_control> allow_threads;
    if (settings.threads > tbb::info::default_concurrency())
        allow_threads.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(settings.threads));
    tbb::task_arena arena(settings.threads == 0 ? tbb::task_arena::automatic : settings.threads);
    arena.execute([&] {
        auto start = Clock::now();
        for_each_pixel_tiled(settings.width, settings.height, [&](int x, int y) {
            primaries[std::size_t(y) * settings.width + x] = renderer.trace_primary(x, y);
        });
        // Rounds of at most kSamplesPerRound samples, round k with pass k. A
        // partial render that ends inside a round (a finished render of fewer
        // samples) has used passes [0, ceil(done / round)); fresh rounds follow
        // them, so no sample is dropped and no random number used twice.
        auto last_checkpoint = Clock::now();
        for (int round = (spp_done + kSamplesPerRound - 1) / kSamplesPerRound; spp_done < settings.spp;
             ++round) {
            const int count = std::min(kSamplesPerRound, settings.spp - spp_done);
            for_each_pixel_tiled(settings.width, settings.height, [&](int x, int y) {
                const std::size_t i = std::size_t(y) * settings.width + x;
                if (primaries[i].found || thin_lens)
                    renderer.trace_shadows(primaries[i], x, y, i, std::uint32_t(round), std::uint32_t(count),
                                           stats[i]);
                stats[i].round_to_float();
            });
            spp_done += count;
            if (settings.on_progress) settings.on_progress(spp_done, settings.spp);
            if (settings.on_checkpoint && spp_done < settings.spp &&
                seconds_since(last_checkpoint) >= settings.checkpoint_interval_s) {
                settings.on_checkpoint(render_so_far(spp_done));
                last_checkpoint = Clock::now();
            }
            if (settings.stop_requested && spp_done < settings.spp && settings.stop_requested()) break;
        }
        measured.first_pass_s = seconds_since(start);
        if (settings.adaptive) {
            start = Clock::now();
            // AAF Sec. 6: the per-pixel totals from the first pass's distances.
            AovSet first_pass(settings.width, settings.height);
            write_aovs(frame, kAovsForAaf, first_pass);
            write_light_attributes(scene.key_light(), first_pass);
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
                if ((primaries[i].found || thin_lens) && remaining > 0)
                    renderer.trace_shadows(primaries[i], x, y, i, kAdaptiveSecondPass,
                                           std::uint32_t(remaining), stats[i]);
            });
            measured.second_pass_s = seconds_since(start);
        }
    });

    if (timings) *timings = measured;
    return render_so_far(spp_done);
}

}  // namespace aaf::trace
