#pragma once

#include <string>

#include "aaf/core/contract/light_plane.h"

namespace aaf::trace {

/// The key light described by a JSON file, for `aaf filter --light` and
/// `aaf info --light` on another renderer's EXR: either one light object of
/// the scene format (libaaf/SCENE_FORMAT.md, "Lights": center, edge_u,
/// edge_v, profile, sigma_m; intensity and color are accepted and unused) or
/// a whole scene file, whose `lights[0]` (the key light) is taken. Checked as
/// the scene loader checks a light. Throws aaf::InputError
/// "<file>: <JSON path>: <problem>".
LightPlane load_light_file(const std::string &path);

}  // namespace aaf::trace
