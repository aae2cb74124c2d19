#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "aaf/core/aaf_params.h"
#include "aaf/core/aov_contract.h"
#include "aaf/core/aov_set.h"
#include "aaf/core/light_plane.h"
#include "aaf/core/sampling_plan.h"

namespace aaf::trace {

/// Groups of AOVs a render can write (`aaf render --aovs`). The beauty R,G,B
/// is always written. Each group is an accumulator (libaaf/trace/aov_group.h,
/// one file each under libaaf/trace/aov_groups/) that may gather per-pixel
/// state from every light sample: the place where later methods add theirs
/// (MAAF's cos/sin accumulations, the ratio estimator's U, S_N, U_N, ISG's
/// hard-shadow and reflection maps).
enum AovGroup : unsigned {
    kAovShadow =
        1u << 0,  ///< shadow.V/d1/d2min/d2max, pixel.spp, pixel.size (+ otherlights.* with several lights)
    kAovPosition = 1u << 1,    ///< P.X/Y/Z
    kAovNormal = 1u << 2,      ///< N.X/Y/Z
    kAovObjectId = 1u << 3,    ///< id.object
    kAovUnshadowed = 1u << 4,  ///< unshadowed.R/G/B
    kAovDepth = 1u << 5,       ///< Z
    kAovAlbedo = 1u << 6,      ///< albedo.R/G/B
    kAovMotion = 1u << 7,      ///< motion.X/Y
    kAovProgress = 1u << 8,    ///< progress.*: the sums a resumed reference continues from
    kAovMaaf = 1u << 9,        ///< maaf.*: MAAF's light-side sums; its first pass is a pass of its own
    /// isg.*, reflect.*, gloss.theta_max, glossy.*, pinhole.*: ISG's maps and
    /// references; traces rays of its own (a glossy reference of spp rays).
    kAovIsg = 1u << 10,
    /// ratio.U/S/Un (+ .Y), summed and per light: the ratio estimator's layer;
    /// traces spp samples per light of its own (MIS of light and GGX).
    kAovRatio = 1u << 11,
    /// ratio.sto.*, ratio.cv.*: the full-stochastic and control-variate
    /// estimates from the ratio group's samples (traced again when both are asked for).
    kAovRatioEstimators = 1u << 12,
    /// maaf6.*: MAAF for combined effects (Sec. 6.2); traces path samples of its own.
    kAovMaaf6 = 1u << 13,
};
/// "all": every group that only records the light samples; maaf (whose first
/// pass changes how the samples are stratified), isg, ratio and
/// ratio_estimators (which trace rays of their own) are asked for by name.
inline constexpr unsigned kAovsAll = (kAovProgress << 1) - 1;

/// Name (as `--aovs` spells it) and contents of each group.
struct AovGroupInfo {
    unsigned group;
    const char *name;
    const char *contents;
};
const std::vector<AovGroupInfo> &aov_group_table();
/// Parses a comma-separated list of group names, names of registered
/// methods (method_registry.h: "aaf" is the groups AAF reads) and "all";
/// throws aaf::Error naming an unknown entry.
unsigned parse_aov_groups(const std::string &list);
/// The groups that write any of `roles` (aov_contract.h), e.g. those a
/// method's declared inputs need; the progress group writes no role.
unsigned aov_groups_writing(const std::vector<Role> &roles);
/// The groups that write the required inputs of the registered method
/// `method` (its declaration is the one place that says what it reads);
/// throws aaf::Error for an unknown method.
unsigned aov_groups_for_method(const std::string &method);
/// The groups as a Markdown table (name, channels, roles, the methods whose
/// `--aovs METHOD` includes it), a generated block of libaaf/AOV_CONTRACT.md.
std::string aov_groups_markdown();

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
    int threads = 0;         ///< 0 = all hardware threads; the result does not depend on it
    double frame = 1;        ///< animation time (scene keyframes), frames
    unsigned aovs = aov_groups_for_method("aaf");

    /// AAF's two-pass adaptive sampling (Sec. 5.1, 6): after the first pass,
    /// each pixel gets the total of AAF Eq. 21 (aaf::plan_samples), capped at max_spp.
    bool adaptive = false;
    int max_spp = SamplingPlanParams{}.max_spp;  ///< cap of the adaptive total per pixel (aaf plan's)
    /// The AAF parameters of the plan: those it shares with the filter that
    /// follows (aaf_plan_parameter_names(): mu, light_bandlimit, light_axes,
    /// projected_pixel) must be the filter's; the others stay at their defaults.
    AafParams plan;

    /// With the maaf group: the samples of MAAF's first pass (Sec. 6.2: 16),
    /// traced as a pass of their own before the rest, whose occluder distances
    /// set the light-side frequencies every sample is accumulated with.
    int maaf_first_pass_spp = 16;
    /// With the maaf6 group: the effects its path samples trace (path_sample.h), any of
    /// "defocus,shadows,indirect"; the others are off (pinhole, the light's centre, no bounce).
    std::string maaf6_effects = "defocus,shadows,indirect";

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

/// Wall-clock seconds of a render's stages (AAF Table 1's columns).
struct RenderTimings {
    double first_pass_s = 0;   ///< primary rays and the first (or only) shadow pass
    double plan_s = 0;         ///< the sampling plan between the passes (adaptive only)
    double second_pass_s = 0;  ///< the remaining shadow samples (adaptive only)
    /// --aovs maaf6: tracing its path samples, and the wedges and sums (MAAF
    /// Sec. 6.2). Timings are reported here, never in the image's header,
    /// so that equal renders stay equal bytes.
    double maaf6_sampling_s = 0, maaf6_prefilter_s = 0;
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
/// frame, and with `adaptive` a finite positive mu, max_spp in [spp, 1048576]
/// and no resume. render_scene() checks this first.
void validate_render_settings(const RenderSettings &settings);

/// Renders a scene, given as a JSON scene file or by name, with Embree and
/// returns the selected AOVs (aov_contract.h) plus the beauty, with the key
/// light and render settings as header attributes. Throws aaf::InputError on
/// a bad scene or resume file and aaf::Error on bad settings.
/// When `timings` is given it receives the stages' durations.
AovSet render_scene(const std::string &scene, const RenderSettings &settings,
                    RenderTimings *timings = nullptr);

}  // namespace aaf::trace
