#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "aaf/core/aov_set.h"
#include "aaf/core/light_plane.h"

namespace aaf::trace {

/// Settings of one render of a built-in scene.
struct RenderSettings {
    int width = 640;
    int height = 480;
    /// Light samples per pixel, stratified over the light. With `adaptive`,
    /// the first pass (AAF Sec. 6 uses 9).
    int spp = 9;
    std::uint64_t seed = 1;  ///< with pixel index and pass, fixes every random number
    int threads = 0;         ///< 0 = all hardware threads; the result does not depend on it

    /// AAF's two-pass adaptive sampling (Sec. 5.1, 6): after the first pass,
    /// each pixel gets the total of Eq. 21 (aaf::plan_samples), capped at max_spp.
    bool adaptive = false;
    float adaptive_mu = 2.0f;  ///< mu of Eq. 21
    int max_spp = 100;         ///< cap of the adaptive total per pixel

    /// Overrides the scene light's emission profile (AAF Sec. 7: uniform lights).
    std::optional<LightProfile> light_profile;
    /// Includes the cosine falloff in the light function l(y) (AAF Sec. 7):
    /// shadow samples are weighted by cos(receiver) cos(light) / r^2 relative to
    /// the light's centre, and r(x) becomes the exact unshadowed irradiance.
    bool cosine_falloff = false;
};

/// Wall-clock seconds of a render's stages (AAF Table 1's columns).
struct RenderTimings {
    double first_pass_s = 0;   ///< primary rays and the first (or only) shadow pass
    double plan_s = 0;         ///< the sampling plan between the passes (adaptive only)
    double second_pass_s = 0;  ///< the remaining shadow samples (adaptive only)
};

/// Names of the built-in procedural scenes.
std::vector<std::string> builtin_scene_names();

/// Renders the built-in scene `scene_name` with Embree and returns every AAF
/// AOV of the contract (aov_contract.h) plus the beauty, with the light and
/// render settings as header attributes. Throws aaf::Error on an unknown scene
/// or bad settings.
/// When `timings` is given it receives the stages' durations.
AovSet render_builtin(const std::string &scene_name, const RenderSettings &settings,
                      RenderTimings *timings = nullptr);

}  // namespace aaf::trace
