#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/aov_set.h"
#include "aaf/core/contract/light_plane.h"
#include "aaf/core/methods/aaf/aaf_params.h"
#include "aaf/core/methods/aaf/sampling_plan.h"
#include "aaf/trace/aov_group_registry.h"

namespace aaf::trace {

/// The AOV groups a render can write (`aaf render --aovs`) are a registry,
/// aov_group_registry.h; the beauty R,G,B is always written.

/// Samples per round of a progressive render: round k uses random-number
/// pass k and its own stratification, so a reference of N * 1024 samples can
/// be stopped after any round and resumed to the same bytes. A partial render
/// that ends inside a round (e.g. 1500 spp) resumes too, keeping its samples
/// and continuing with the next unused pass; the result is then statistically
/// equivalent to, but not byte-identical with, a render in one go.
inline constexpr int kSamplesPerRound = 1024;

/// Settings of one render.
struct RenderSettings {
    int width = 640;
    int height = 480;
    /// Light samples per pixel, stratified over the light, in rounds of
    /// kSamplesPerRound. With `adaptive`, the first pass (AAF Sec. 6 uses 9).
    int spp = 9;
    std::uint64_t seed = 1;  ///< with pixel index and pass, fixes every random number
    /// Draws with frame_seed(seed, frame) instead of `seed`, so that the
    /// frames of a sequence get independent noise (`aaf render --frames`
    /// sets it unless --fixed-noise); the header then records both.
    bool seed_per_frame = false;
    int threads = 0;   ///< 0 = all hardware threads; the result does not depend on it
    double frame = 1;  ///< animation time (scene keyframes), frames
    AovGroups aovs = aov_groups_for_method("aaf");  ///< beside the beauty; by default the groups AAF reads
    /// The values of the groups' own parameters (AovGroupInfo::parameters):
    /// maaf's first-pass samples, maaf6's effects, a plug-in group's own.
    AovGroupParameters group_parameters;

    /// AAF's two-pass adaptive sampling (Sec. 5.1, 6): after the first pass,
    /// each pixel gets the total of AAF Eq. 21 (aaf::plan_samples), capped at max_spp.
    bool adaptive = false;
    int max_spp = SamplingPlanParams{}.max_spp;  ///< cap of the adaptive total per pixel (aaf plan's)
    /// The AAF parameters of the plan: those it shares with the filter that
    /// follows (aaf_plan_parameter_names(): mu, light_bandlimit, light_axes,
    /// projected_pixel) must be the filter's; the others stay at their defaults.
    AafParams plan;

    /// Overrides the lights' emission profile (AAF Sec. 7: uniform lights).
    std::optional<LightProfile> light_profile;
    /// Includes the cosine falloff in the key light's function l(y) (AAF
    /// Sec. 7): shadow samples are weighted by cos(receiver) cos(light) / r^2
    /// relative to the light's centre, and r(x) becomes the exact unshadowed irradiance.
    bool cosine_falloff = false;
    /// A light sample behind the receiver's own tangent plane is occluded (the
    /// visibility counts it as blocked) and by default gives an occluder at
    /// the receiver, d2 = d1 (s2 = 0: such pixels are barely filtered and get
    /// AAF Eq. 21's largest rate). True: it gives no occluder distance, as the AAF
    /// authors' code skips it; the study measured that no better on any scene
    /// and worse on curved receivers (their terminators then keep the first
    /// pass's 9 samples unfiltered), scripts/study/RESULTS.md.
    bool skip_self_occluded = false;

    /// Progressive rendering: a render already holding some rounds (the
    /// output of an earlier render of the same scene, seed, size and frame,
    /// with the progress AOVs) to continue from instead of starting over.
    const AovSet *resume = nullptr;
    std::string resume_source;  ///< where `resume` was read from, to name it in errors
    /// Called after each round with the samples per pixel done so far and the target.
    std::function<void(int done_spp, int total_spp)> on_progress;
    /// Called during each round, as its tiles finish (at most 32 times a
    /// round, one call at a time, from a worker thread), with the samples per
    /// pixel done so far counting the round's finished share: a progress
    /// display between the rounds' on_progress calls. Values may repeat.
    std::function<void(double done_spp, int total_spp)> on_round_progress;
    /// Called with the complete AOVs of the render so far (progress AOVs
    /// included) at most every `checkpoint_interval_s` seconds between rounds.
    std::function<void(const AovSet &partial)> on_checkpoint;
    double checkpoint_interval_s = 60;
    /// Asked after each round of a progressive render; when it returns true the
    /// render stops there and returns the AOVs so far (aaf:spp_done < aaf:spp),
    /// which `resume` continues.
    std::function<bool()> stop_requested;
};

/// The seed frame `frame` of a sequence draws with: SplitMix64's finaliser
/// (a bijective 64-bit mix) of `seed` xor the mix of the frame's IEEE-754
/// bits, kept to its low 31 bits so that the int header attribute aaf:seed
/// holds it exactly. Any two frames get unrelated seeds; the same frame
/// and seed always the same one.
std::uint64_t frame_seed(std::uint64_t seed, double frame);
/// The seed `settings` draws with: frame_seed(seed, frame) with
/// seed_per_frame, else seed.
std::uint64_t effective_seed(const RenderSettings &settings);

/// Wall-clock seconds of a render's stages (AAF Table 1's columns).
struct RenderTimings {
    double scene_s = 0;        ///< reading the scene file and building its meshes
    double setup_s = 0;        ///< Embree's BVH and the AOV groups' per-pixel state
    double primaries_s = 0;    ///< the primary (camera) rays, part of first_pass_s
    double first_pass_s = 0;   ///< primary rays and the first (or only) shadow pass
    double plan_s = 0;         ///< the sampling plan between the passes (adaptive only)
    double second_pass_s = 0;  ///< the remaining shadow samples (adaptive only)
    /// --aovs maaf6: tracing its path samples, and the wedges and sums (MAAF
    /// Sec. 6.2). Timings are reported here, never in the image's header,
    /// so that equal renders stay equal bytes.
    double maaf6_sampling_s = 0, maaf6_prefilter_s = 0;
    /// Assembling the AOV set (every group's channels and the header) after the last pass.
    double aovs_s = 0;
};

/// Names of the scenes found in the scene directories (built-in: the
/// project's testdata/scenes), for `aaf render --list`.
std::vector<std::string> builtin_scene_names();

/// The files rendering `scene` (a JSON scene file or a name) reads: the
/// scene file, then each OBJ file it loads; so that a caller can refuse to
/// write its output over one of them. Throws aaf::InputError for an unknown
/// name or malformed JSON.
std::vector<std::string> scene_input_files(const std::string &scene);

/// The earliest key frame of `scene`'s animation (the camera's or any
/// light's track), none for a scene without animation. Throws
/// aaf::InputError for an unknown name or a malformed scene.
std::optional<double> scene_first_key_frame(const std::string &scene);

/// Throws aaf::Error naming the first setting outside its range: width and
/// height in [1, 16384], spp in [1, 1048576], threads in [0, 1024], a finite
/// frame, with `adaptive` a finite positive mu, max_spp in [spp, 1048576]
/// and no resume, no resume with a group that cannot be resumed, and values
/// of each group's parameters that it accepts. render_scene() checks this first.
void validate_render_settings(const RenderSettings &settings);

/// Renders a scene, given as a JSON scene file or by name, with Embree and
/// returns the selected AOVs (aov_contract.h) plus the beauty, with the key
/// light and render settings as header attributes (aaf:seed the seed drawn
/// with, and with seed_per_frame aaf:base_seed the settings' seed). Throws aaf::InputError on
/// a bad scene or resume file and aaf::Error on bad settings.
/// When `timings` is given it receives the stages' durations.
AovSet render_scene(const std::string &scene, const RenderSettings &settings,
                    RenderTimings *timings = nullptr);

}  // namespace aaf::trace
