#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "aaf/core/aov_set.h"

namespace aaf::trace {

/// Settings of one render of a built-in scene.
struct RenderSettings {
    int width = 640;
    int height = 480;
    int spp = 9;             ///< light samples per pixel, stratified over the light
    std::uint64_t seed = 1;  ///< with pixel index and pass, fixes every random number
    int threads = 0;         ///< 0 = all hardware threads; the result does not depend on it
};

/// Names of the built-in procedural scenes (`grids`, ...).
std::vector<std::string> builtin_scene_names();

/// Renders the built-in scene `scene_name` with Embree and returns every AAF
/// AOV of the contract (aov_contract.h) plus the beauty, with the light and
/// render settings as header attributes. Throws aaf::Error on an unknown scene
/// or bad settings.
AovSet render_builtin(const std::string &scene_name, const RenderSettings &settings);

}  // namespace aaf::trace
