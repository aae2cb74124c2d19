#include "aaf/trace/render.h"

#include <pmmintrin.h>  // flush-to-zero and denormals-are-zero
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/methods/aaf/aaf_roles.h"
#include "aaf/core/methods/aaf/sampling_plan.h"
#include "aaf/core/methods/maaf6/maaf6_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"
#include "aov_group.h"
#include "random.h"
#include "renderer.h"
#include "scene_description.h"
#include "scene_file.h"
#include "scene_hash.h"

namespace aaf::trace {

namespace {

constexpr int kTileSize = 16;
/// Random-number pass of the adaptive second pass, apart from the rounds' passes.
constexpr std::uint32_t kAdaptiveSecondPass = 1u << 30;

/// Calls `body(x0, x1, y)` for every row span of every 16x16 tile (clipped
/// at the image's edges), one tile per task. Each pixel is in exactly one
/// span, so results do not depend on the schedule.
template <typename Body>
void for_each_tile_row(int width, int height, const Body &body,
                       const std::function<void(double)> &on_share_done = {}) {
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    const int tiles_y = (height + kTileSize - 1) / kTileSize;
    const int tiles_total = tiles_x * tiles_y;
    std::atomic<int> tiles_done{0};
    std::mutex reporting;
    parallel_for_each_index(tiles_total, [&](int tile) {
        // Denormals only slow the traversal down; flush them on every worker.
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
        const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
        const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
        for (int y = y0; y < y1; ++y) body(x0, x1, y);
        if (!on_share_done) return;
        // A report each time the finished share crosses a 32nd.
        const int done = ++tiles_done;
        if (done * 32 / tiles_total == (done - 1) * 32 / tiles_total) return;
        const std::lock_guard<std::mutex> lock(reporting);
        on_share_done(double(done) / tiles_total);
    });
}

/// for_each_tile_row() pixel by pixel: `body(x, y)`.
template <typename Body>
void for_each_pixel_tiled(int width, int height, const Body &body,
                          const std::function<void(double)> &on_share_done = {}) {
    for_each_tile_row(
        width, height,
        [&](int x0, int x1, int y) {
            for (int x = x0; x < x1; ++x) body(x, y);
        },
        on_share_done);
}

using Accumulators = std::vector<std::unique_ptr<AovAccumulator>>;

/// Writes the beauty (the first) and those of `accumulators`' groups in `groups`, in order.
void write_aovs(const RenderState &state, const Accumulators &accumulators, const AovGroups &groups,
                AovSet &aovs) {
    for (std::size_t i = 0; i < accumulators.size(); ++i)
        if (i == 0 || groups.contains(accumulators[i]->info().name)) accumulators[i]->write(state, aovs);
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
        aovs.attributes[attr::kAdaptiveMu] = settings.plan.mu;
        aovs.attributes[attr::kMaxSpp] = settings.max_spp;
    }
    aovs.attributes[attr::kCosineFalloff] = int(settings.cosine_falloff);
}

/// Returns the samples per pixel of a partial render; throws
/// aaf::InputError when it is not a partial render of the same scene, seed,
/// size, frame and light, or when the scene's content changed since
/// (scene_hash.h). `fail` throws with the problem.
template <typename Fail>
int check_resumable(const AovSet &partial, const SceneDescription &scene, const RenderSettings &settings,
                    const Fail &fail) {
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
    if (*done < 0) fail("header attribute 'aaf:spp_done' is negative");
    if (*done > settings.spp) fail("it already has " + std::to_string(*done) + " spp, more than --spp");
    return *done;
}

/// Restores the per-pixel state of a partial render through the groups that
/// keep some (shadow, progress) and returns its samples per pixel; throws
/// aaf::InputError as check_resumable() does, or naming a missing channel.
int restore_progress(const AovSet &partial, const SceneDescription &scene, const RenderSettings &settings,
                     const Accumulators &accumulators, std::vector<ShadowStats> &stats) {
    auto fail = [&](const std::string &problem) {
        const std::string &source = settings.resume_source;
        throw InputError((source.empty() ? "" : source + ": ") + "cannot resume: " + problem);
    };
    const int done = check_resumable(partial, scene, settings, fail);
    for (const std::unique_ptr<AovAccumulator> &accumulator : accumulators)
        for (const std::string &name : accumulator->resume_channels())
            if (!partial.has_channel(name))
                fail("it has no channel '" + name + "' (render with --aovs including progress)");
    for (const std::unique_ptr<AovAccumulator> &accumulator : accumulators)
        accumulator->restore(partial, stats);
    return done;
}

/// One render's per-pixel state and how it is traced: the primary hits, the
/// rounds of shadow samples and the adaptive second pass, with the sample
/// hooks of the groups that want them around each pixel's batch.
class Tracing {
  public:
    Tracing(const SceneDescription &scene, const RenderSettings &settings, const Accumulators &accumulators)
        : scene_(scene),
          settings_(settings),
          renderer_(scene, settings),
          primaries_(std::size_t(settings.width) * settings.height),
          stats_(primaries_.size()) {
        for (const std::unique_ptr<AovAccumulator> &accumulator : accumulators) {
            accumulator->begin_render(primaries_.size());
            if (accumulator->wants_samples()) listeners_.push_back(accumulator.get());
            listeners_want_distances_ = listeners_want_distances_ || accumulator->wants_occluder_distances();
        }
    }

    RenderState state(const Camera &previous_camera) const {
        return {
            scene_,          previous_camera,  primaries_, stats_,        renderer_.has_separate_radiance(),
            settings_.width, settings_.height, &renderer_, settings_.spp, settings_.seed};
    }
    std::vector<ShadowStats> &stats() { return stats_; }

    void trace_primaries() {
        for_each_tile_row(settings_.width, settings_.height, [&](int x0, int x1, int y) {
            renderer_.trace_primaries(y, x0, x1, &primaries_[std::size_t(y) * settings_.width + x0]);
        });
    }

    /// Traces `count` samples of pass `pass` for every pixel that has a
    /// receiver or a lens, or for pixel (x, y) only `count(x, y)` of them;
    /// with occluder distances when `stats_distances` or a listener wants them.
    template <typename Count>
    void trace_pass(std::uint32_t pass, const Count &count, bool round_to_float, bool stats_distances,
                    const std::function<void(double)> &on_share_done = {}) {
        const bool distances = stats_distances || listeners_want_distances_;
        const bool thin_lens = scene_.camera.is_thin_lens();
        for_each_pixel_tiled(
            settings_.width, settings_.height,
            [&](int x, int y) {
                const std::size_t i = std::size_t(y) * settings_.width + x;
                const int samples = count(x, y);
                if ((primaries_[i].found || thin_lens) && samples > 0) {
                    for (AovAccumulator *listener : listeners_) listener->begin_pixel(i, primaries_[i]);
                    renderer_.trace_shadows(primaries_[i], x, y, i, pass, std::uint32_t(samples), distances,
                                            stats_[i], listeners_);
                    for (AovAccumulator *listener : listeners_) listener->end_pixel(i);
                }
                if (round_to_float) stats_[i].round_to_float();
            },
            on_share_done);
    }

  private:
    const SceneDescription &scene_;
    const RenderSettings &settings_;
    const Renderer renderer_;
    std::vector<PrimaryHit> primaries_;
    std::vector<ShadowStats> stats_;
    std::vector<AovAccumulator *> listeners_;
    bool listeners_want_distances_ = false;
};

/// The groups a render writes: those asked for, plus what resuming needs.
AovGroups groups_to_write(const RenderSettings &settings) {
    AovGroups groups = settings.aovs;
    // A reference (a round or more) can always be resumed to more samples.
    if (!settings.adaptive && (settings.spp >= kSamplesPerRound || settings.resume))
        groups.insert("progress");
    // Resuming needs the spp and occluder distances beside the sums.
    if (groups.contains("progress")) groups.insert("shadow");
    return groups;
}

/// Samples of the first round: the largest first pass a written group asks
/// for (MAAF's, Sec. 6.2, is a round of its own, stratified by itself), at
/// most spp; 0 for none.
int first_pass_spp(const Accumulators &accumulators, const AovGroups &groups, int spp) {
    int first_pass = 0;
    for (const std::unique_ptr<AovAccumulator> &accumulator : accumulators)
        if (groups.contains(accumulator->info().name))
            first_pass = std::max(first_pass, accumulator->first_pass_spp());
    return std::min(first_pass, spp);
}

/// Per-pixel totals of AAF's adaptive sampling (Sec. 6) from the first pass's distances.
AovSet plan_second_pass(const RenderState &state, const Accumulators &accumulators,
                        const RenderSettings &settings) {
    AovSet first_pass(settings.width, settings.height);
    write_aovs(state, accumulators, aov_groups_for_method("aaf"), first_pass);
    write_light_attributes(state.scene.key_light(), first_pass);
    SamplingPlanParams params;
    params.first_pass_spp = settings.spp;
    params.max_spp = settings.max_spp;
    return plan_samples_aovs(first_pass, ChannelMap(), settings.plan, params);
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Traces rounds of at most kSamplesPerRound samples from `spp_done` on (the
/// first `first_pass` of them a round of their own) until settings.spp or a
/// stop, reporting and checkpointing (`render_so_far`) between them; returns
/// the samples per pixel done. Round k uses pass k: a partial render that
/// ends inside a round (a finished render of fewer samples) has used passes
/// [0, ceil(done / round)); fresh rounds follow them, so no sample is
/// dropped and no random number used twice.
int trace_rounds(Tracing &tracing, const RenderSettings &settings, int spp_done, int first_pass,
                 bool stats_distances, const std::function<AovSet(int)> &render_so_far) {
    auto last_checkpoint = Clock::now();
    for (int round = (spp_done + kSamplesPerRound - 1) / kSamplesPerRound; spp_done < settings.spp; ++round) {
        const int count = spp_done < first_pass ? first_pass - spp_done
                                                : std::min(kSamplesPerRound, settings.spp - spp_done);
        std::function<void(double)> on_share_done;
        if (settings.on_round_progress)
            on_share_done = [&](double share) {
                settings.on_round_progress(spp_done + share * count, settings.spp);
            };
        tracing.trace_pass(
            std::uint32_t(round), [&](int, int) { return count; }, true, stats_distances && round == 0,
            on_share_done);
        spp_done += count;
        if (settings.on_progress) settings.on_progress(spp_done, settings.spp);
        if (settings.on_checkpoint && spp_done < settings.spp &&
            seconds_since(last_checkpoint) >= settings.checkpoint_interval_s) {
            settings.on_checkpoint(render_so_far(spp_done));
            last_checkpoint = Clock::now();
        }
        if (settings.stop_requested && spp_done < settings.spp && settings.stop_requested()) break;
    }
    return spp_done;
}

/// The AOV set of a render that has taken `done` samples per pixel: the
/// beauty and `groups`' channels, and the header. `given` are the settings
/// as the caller gave them (`settings` with the effective seed). The maaf6
/// group's timings move from the header to `measured`: equal renders are
/// equal bytes.
AovSet assemble_aovs(const RenderState &state, const Accumulators &accumulators, const AovGroups &groups,
                     const RenderSettings &settings, const RenderSettings &given, int done,
                     RenderTimings &measured) {
    AovSet aovs(settings.width, settings.height);
    write_aovs(state, accumulators, groups, aovs);
    write_attributes(state.scene, settings, done, aovs);
    if (given.seed_per_frame) aovs.attributes[attr::kBaseSeed] = int(given.seed);
    for (auto [name, seconds] : {std::pair{attr::kMaaf6SamplingS, &measured.maaf6_sampling_s},
                                 std::pair{attr::kMaaf6PrefilterS, &measured.maaf6_prefilter_s}}) {
        auto it = aovs.attributes.find(name);
        if (it == aovs.attributes.end()) continue;
        if (const float *value = std::get_if<float>(&it->second)) *seconds = double(*value);
        aovs.attributes.erase(it);
    }
    return aovs;
}

/// `given` drawing with its effective seed (seed_per_frame done).
RenderSettings with_effective_seed(const RenderSettings &given) {
    RenderSettings settings = given;
    settings.seed = effective_seed(given);
    settings.seed_per_frame = false;
    return settings;
}

}  // namespace

std::uint64_t frame_seed(std::uint64_t seed, double frame) {
    std::uint64_t frame_bits = 0;
    static_assert(sizeof frame_bits == sizeof frame);
    std::memcpy(&frame_bits, &frame, sizeof frame);
    return mix64(seed ^ mix64(frame_bits)) & 0x7fffffffu;
}

std::uint64_t effective_seed(const RenderSettings &settings) {
    return settings.seed_per_frame ? frame_seed(settings.seed, settings.frame) : settings.seed;
}

std::vector<std::string> scene_input_files(const std::string &scene) {
    return scene_file_inputs(resolve_scene(scene));
}

std::optional<double> scene_first_key_frame(const std::string &scene) {
    // The size only shapes the camera's aspect, which the keys do not depend on.
    const SceneDescription description = load_scene_file(resolve_scene(scene), 16, 16);
    std::optional<double> first;
    const auto consider = [&first](double frame) { first = first ? std::min(*first, frame) : frame; };
    if (!description.animation.camera.empty()) consider(description.animation.camera.front().frame);
    for (const std::vector<LightKey> &keys : description.animation.lights)
        if (!keys.empty()) consider(keys.front().frame);
    for (const std::vector<ObjectKey> &keys : description.animation.meshes)
        if (!keys.empty()) consider(keys.front().frame);
    return first;
}

void validate_render_settings(const RenderSettings &settings) {
    if (settings.width < 1 || settings.width > 16384 || settings.height < 1 || settings.height > 16384)
        throw Error("image width and height must lie in [1, 16384] pixels");
    if (settings.spp < 1 || settings.spp > (1 << 20)) throw Error("spp must lie in [1, 1048576]");
    if (settings.threads < 0 || settings.threads > 1024)
        throw Error("threads must lie in [0, 1024] (0 = all cores)");
    if (!std::isfinite(settings.frame)) throw Error("frame must be finite");
    if (settings.adaptive) {
        if (settings.max_spp < settings.spp || settings.max_spp > (1 << 20))
            throw Error("max spp must lie in [spp, 1048576] for adaptive sampling");
        if (!(settings.plan.mu > 0) || !std::isfinite(settings.plan.mu))
            throw Error("adaptive mu must be positive and finite");
        if (settings.resume) throw Error("an adaptive render cannot be resumed");
    }
    for (const std::string &group : settings.aovs.names()) {
        const std::string &why = find_aov_group(group).not_resumable_because;
        if (settings.resume && !why.empty())
            throw Error("a render with the " + group + " AOVs cannot be resumed (" + why + ")");
    }
    // Each group refuses values of its parameters it cannot use.
    make_aov_accumulators(settings.aovs, settings.group_parameters);
}

AovSet render_scene(const std::string &scene_name, const RenderSettings &given, RenderTimings *timings) {
    validate_render_settings(given);
    RenderTimings measured;
    auto start = Clock::now();
    const RenderSettings settings = with_effective_seed(given);
    SceneDescription scene = load_scene_file(resolve_scene(scene_name), settings.width, settings.height);
    scene.set_frame(settings.frame);
    if (settings.light_profile)
        for (SceneLight &light : scene.lights) light.plane.profile = *settings.light_profile;
    const Camera previous_camera = scene.camera_at(settings.frame - 1);

    const AovGroups groups = groups_to_write(settings);
    // The adaptive plan reads the AAF groups, whether written or not.
    const Accumulators accumulators = make_aov_accumulators(
        settings.adaptive ? groups | aov_groups_for_method("aaf") : groups, settings.group_parameters);
    measured.scene_s = seconds_since(start);
    start = Clock::now();
    Tracing tracing(scene, settings, accumulators);
    measured.setup_s = seconds_since(start);
    const RenderState state = tracing.state(previous_camera);
    int spp_done = settings.resume
                       ? restore_progress(*settings.resume, scene, settings, accumulators, tracing.stats())
                       : 0;
    const int first_pass = first_pass_spp(accumulators, groups, settings.spp);
    // d2min/d2max are statistics of the first round, the sparse first pass
    // AAF takes d1 and d2 from (AAF Sec. 6); later rounds and the adaptive
    // second pass need visibility only, which any hit answers.
    const bool stats_distances = groups.contains("shadow") || settings.adaptive;
    auto render_so_far = [&](int done) {
        return assemble_aovs(state, accumulators, groups, settings, given, done, measured);
    };

    // oneTBB caps its workers at the hardware's threads (and warns) unless the
    // process-wide limit is raised: raise it for this render, so `threads`
    // really run (a 1-core machine still checks 1 vs 2 threads).
    std::optional<tbb::global_control> allow_threads;
    if (settings.threads > tbb::info::default_concurrency())
        allow_threads.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(settings.threads));
    tbb::task_arena arena(settings.threads == 0 ? tbb::task_arena::automatic : settings.threads);
    arena.execute([&] {
        start = Clock::now();
        tracing.trace_primaries();
        measured.primaries_s = seconds_since(start);
        spp_done = trace_rounds(tracing, settings, spp_done, first_pass, stats_distances, render_so_far);
        measured.first_pass_s = seconds_since(start);
        if (settings.adaptive) {
            start = Clock::now();
            const AovSet plan = plan_second_pass(state, accumulators, settings);
            const ConstPlaneView totals = plan.channel(ChannelMap().channel(roles::PlannedSpp));
            measured.plan_s = seconds_since(start);
            start = Clock::now();
            tracing.trace_pass(
                kAdaptiveSecondPass, [&](int x, int y) { return int(totals(x, y)) - settings.spp; }, false,
                false);
            measured.second_pass_s = seconds_since(start);
        }
    });

    // In the arena too: a group that traces while it writes (isg) keeps to `threads`.
    AovSet result;
    start = Clock::now();
    arena.execute([&] { result = render_so_far(spp_done); });
    measured.aovs_s = seconds_since(start);
    if (timings) *timings = measured;
    return result;
}

}  // namespace aaf::trace
