#include "light_sampler.h"

namespace aaf::trace {

namespace {

/// Half the rectangle's extent in units of sigma: where the Gaussian is cut.
/// A uniform light never reads its truncated normals; any valid limit will do.
double truncation_sigmas(const LightPlane &light, float extent_m) {
    light.validate();
    return light.profile == LightProfile::Gaussian ? 0.5 * double(extent_m) / double(light.sigma_m) : 1.0;
}

}  // namespace

LightSampler::LightSampler(const LightPlane &light)
    : light_(light),
      gaussian_(light.profile == LightProfile::Gaussian),
      square_(light.width_m == light.height_m),
      normal_u_(truncation_sigmas(light, light.width_m)),
      normal_v_(square_ ? 1.0 : truncation_sigmas(light, light.height_m)) {}

}  // namespace aaf::trace
