#include "aaf/core/kernels/shadow_composition.h"

namespace aaf {

void compose_shadowed_beauty(const MethodImages &images, ConstPlaneView filtered_visibility) {
    const bool other_lights = images.has(Role::OtherLights);
    for (std::size_t c = 0; c < 3; ++c) {
        const ConstPlaneView r = images.input(Role::Unshadowed, c);
        const PlaneView beauty = images.output(Role::Beauty, c);
        for (int y = 0; y < images.height(); ++y)
            for (int x = 0; x < images.width(); ++x)
                beauty(x, y) = r(x, y) * filtered_visibility(x, y);  // AAF Eq. 1
        if (!other_lights) continue;
        const ConstPlaneView other = images.input(Role::OtherLights, c);
        for (int y = 0; y < images.height(); ++y)
            for (int x = 0; x < images.width(); ++x) beauty(x, y) += other(x, y);
    }
}

}  // namespace aaf
