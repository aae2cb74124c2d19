#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/aov_set.h"
#include "aaf/trace/render.h"
#include "light_sample.h"
#include "renderer.h"
#include "scene_description.h"

namespace aaf::trace {

/// What every render keeps per pixel, whatever its AOV groups, and what the
/// groups write from: the primary hits and the key light's sums over every
/// round so far (the beauty, the adaptive plan and a resumption need them).
struct RenderState {
    const SceneDescription &scene;
    const Camera &previous_camera;  ///< for motion vectors
    const std::vector<PrimaryHit> &primaries;
    const std::vector<ShadowStats> &stats;
    bool separate_radiance;  ///< Renderer::has_separate_radiance()
    int width;
    int height;
    /// The render's tracer, settings and seed, for groups that trace rays of
    /// their own when they write (isg); null in tests that build a state by hand.
    const Renderer *renderer = nullptr;
    int spp = 0;
    std::uint64_t seed = 0;

    /// Calls `body(x, y, primary, stats)` for every pixel, rows in parallel
    /// (on the current oneTBB arena): a body may write only pixel (x, y)'s
    /// outputs, so the result does not depend on the thread count. Assembling
    /// a frame's AOVs touches tens of MiB for the first time; one thread at a
    /// time made it a serial stage of every render.
    template <typename Body>
    void for_each_pixel(const Body &body) const {
        for_each_row(height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * width + x;
                body(x, y, primaries[i], stats[i]);
            }
        });
    }

  private:
    /// Calls `row(y)` for every y in [0, height), rows in parallel.
    static void for_each_row(int height, const std::function<void(int)> &row);
};

/// One AOV group (aov_group_registry.h, `aaf render --aovs`) as an
/// accumulator: it may gather per-pixel state from every light sample, and
/// it writes its channels into the render's AovSet. An accumulator lives for
/// one render, so state it owns persists across the progressive rounds.
/// Groups that write from RenderState alone leave the sample hooks as they
/// are and cost nothing per sample; the renderer calls the hooks only of the
/// groups whose wants_samples() is true.
class AovAccumulator {
  public:
    virtual ~AovAccumulator() = default;

    /// Its declaration, as aov_group_table() lists it: `--aovs` name,
    /// contents, roles (those of roles()), parameters.
    virtual AovGroupInfo info() const = 0;
    /// The aaf::Roles whose channels it writes (aov_contract.h); empty for a
    /// group whose channels are the tracer's own (progress).
    virtual std::vector<Role> roles() const = 0;

    /// Takes the values of its declared parameters (info().parameters),
    /// before begin_render(); throws aaf::Error for a value it cannot use
    /// (validate_render_settings() asks this of every group of a render).
    virtual void set_parameters(const ParameterSet &values) { (void)values; }
    /// Samples of a first pass it needs traced as a round of its own (its
    /// own stratification) before the rest, e.g. MAAF's (Sec. 6.2); 0 for none.
    virtual int first_pass_spp() const { return 0; }

    /// Whether begin_pixel, add_sample and end_pixel are to be called.
    virtual bool wants_samples() const { return false; }
    /// Whether its samples need their occluder distance d2_m in every pass (a
    /// closest-hit query per shadow ray); otherwise passes after the first
    /// round trace visibility only and hand it samples with d2_m = 0.
    virtual bool wants_occluder_distances() const { return wants_samples(); }
    /// Sizes its per-pixel state for `pixel_count` pixels (row-major), once,
    /// before any sample; with a resumption, before restore().
    virtual void begin_render(std::size_t pixel_count) { (void)pixel_count; }
    /// Starts a batch of samples (one round, or the adaptive second pass) of
    /// pixel `pixel`, whose primary hit is `primary` (primary.found is false
    /// for a thin lens's background pixel). Calls for different pixels run
    /// concurrently: each may touch only the state of its own pixel.
    virtual void begin_pixel(std::size_t pixel, const PrimaryHit &primary) {
        (void)pixel;
        (void)primary;
    }
    /// Adds one sample of pixel `pixel` (light_sample.h for its fields).
    virtual void add_sample(std::size_t pixel, const LightSample &sample) {
        (void)pixel;
        (void)sample;
    }
    /// Ends the batch of pixel `pixel`. A group that writes sums a checkpoint
    /// stores in float rounds them to float here, so that a resumed render
    /// continues from exactly the state it would have had.
    virtual void end_pixel(std::size_t pixel) { (void)pixel; }

    /// Adds its channels to `aovs` (which has `state`'s size) and writes every pixel.
    virtual void write(const RenderState &state, AovSet &aovs) const = 0;

    /// Channels a partial render must hold for restore(); empty when the
    /// group keeps nothing a resumption continues from.
    virtual std::vector<std::string> resume_channels() const { return {}; }
    /// Restores its part of the per-pixel state from `partial`, which holds
    /// every resume_channels() entry and has `stats`' size.
    virtual void restore(const AovSet &partial, std::vector<ShadowStats> &stats) {
        (void)partial;
        (void)stats;
    }
};

/// A declaration of the group `name` writing `contents` (in words) through
/// `roles`; parameters none, resumable.
inline AovGroupInfo group_info(std::string name, std::string contents, std::vector<Role> roles) {
    AovGroupInfo info;
    info.name = std::move(name);
    info.contents = std::move(contents);
    info.roles = std::move(roles);
    return info;
}

/// The beauty's accumulator followed by those of `groups`, in
/// aov_group_table()'s order (the order of the channels), each given its
/// values from `parameters`.
std::vector<std::unique_ptr<AovAccumulator>> make_aov_accumulators(const AovGroups &groups,
                                                                   const AovGroupParameters &parameters = {});

/// Registers a group from outside the tracer's list (a plug-in, a test): one
/// line at namespace scope of the group's own file,
/// `static const AovGroupRegistration r([] { return std::unique_ptr<AovAccumulator>(new MyGroup); });`.
/// Its channels follow the built-in groups'. Throws aaf::Error (at start-up)
/// when its name is taken, "all", or not lower-case [a-z0-9_-], or one of its
/// parameters is named as another group's.
class AovGroupRegistration {
  public:
    using Maker = std::unique_ptr<AovAccumulator> (*)();
    explicit AovGroupRegistration(Maker make);
};

/// Writable views of the contract's channels for one role, stored at `precision`.
std::vector<PlaneView> add_role_channels(AovSet &aovs, Role role, Precision precision = Precision::Float);

/// Writes `v` into the first three views at (x, y).
inline void set3(const std::vector<PlaneView> &views, int x, int y, Vec3 v) {
    views[0](x, y) = v.x;
    views[1](x, y) = v.y;
    views[2](x, y) = v.z;
}

}  // namespace aaf::trace
