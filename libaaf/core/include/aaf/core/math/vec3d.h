#pragma once

#include "aaf/core/math/vec3.h"

namespace aaf {

/// A double-precision 3-vector for the analytic light integrals, whose edge
/// terms lose digits in float for small or distant lights (NOTES-RATIO.md).
using Vec3d = Vector3<double>;

}  // namespace aaf
