#pragma once

#include "aaf/core/framework/method.h"

namespace aaf {

/// AAF Eq. 1: the beauty h(x) = r(x) V(x), the unshadowed shading (Role::Unshadowed)
/// times a filtered light-weighted visibility, plus, when the renderer wrote
/// it, the other lights' unfiltered shading (Role::OtherLights). Writes the
/// Role::Beauty output of `images`; shared by the methods that filter visibility.
void compose_shadowed_beauty(const MethodImages &images, ConstPlaneView filtered_visibility);

}  // namespace aaf
