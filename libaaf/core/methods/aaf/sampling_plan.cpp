#include "aaf/core/methods/aaf/sampling_plan.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "aaf/core/kernels/light_bandlimit.h"
#include "aaf/core/methods/aaf/aaf_bandlimits.h"
#include "aaf/core/methods/aaf/aaf_roles.h"
#include "aaf/core/methods/aaf/occluder_fill.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

void plan_samples(const SamplingPlanInputs &in, const LightPlane &light, const AafParams &aaf,
                  const SamplingPlanParams &params, PlaneView spp_out) {
    aaf.validate();
    if (params.first_pass_spp < 1 || params.max_spp < params.first_pass_spp)
        throw Error("sampling plan needs 1 <= first-pass spp <= max spp");
    // The filter's band-limit (aaf_filter.cpp): the plan samples for the filter that will run.
    const LightBandlimitAxes light_sigma_m = aaf_light_sigmas_m(light, aaf);
    const int width = in.d1.width, height = in.d1.height;
    for (ConstPlaneView view : {in.d2_min, in.d2_max, in.object_id, in.pixel_size, ConstPlaneView(spp_out)})
        if (!view.valid() || view.width != width || view.height != height)
            throw Error("sampling plan inputs and output must all be " + std::to_string(width) + "x" +
                        std::to_string(height));

    const bool has_normal = in.normal[0].valid() && in.normal[1].valid() && in.normal[2].valid();
    for (const ConstPlaneView &view : in.normal)
        if (view.valid() && !(has_normal && view.width == width && view.height == height))
            throw Error("sampling plan normal must have all three channels, " + std::to_string(width) + "x" +
                        std::to_string(height));
    const FilledOccluders occluders =
        fill_occluder_distances(in.d2_min, in.d2_max, in.object_id, aaf.fill_radius_px);
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            const float d1 = in.d1(x, y);
            float pixel_size = in.pixel_size(x, y);
            // The filter's footprint (aaf_filter.cpp): the plan samples for the filter that will run.
            if (aaf.projected_pixel && has_normal && std::isfinite(pixel_size))
                pixel_size = projected_pixel_size_m(
                    pixel_size, Vec3{in.normal[0](x, y), in.normal[1](x, y), in.normal[2](x, y)},
                    light.normal);
            float n = float(params.first_pass_spp);
            if (in.object_id(x, y) != 0 && d1 > 0 && pixel_size > 0 && std::isfinite(pixel_size) &&
                has_occluder(occluders.d2_max_m[i])) {
                const float rate = aaf_bandlimits_axes(d1, occluders.d2_min_m[i], occluders.d2_max_m[i],
                                                       pixel_size, light_sigma_m, aaf)
                                       .samples_per_pixel;
                if (std::isfinite(rate))
                    n = std::ceil(rate);
                else
                    n = float(params.max_spp);
            }
            spp_out(x, y) = std::clamp(n, float(params.first_pass_spp), float(params.max_spp));
        }
    });
}

AovSet plan_samples_aovs(const AovSet &first_pass, const ChannelMap &requested, const AafParams &aaf,
                         const SamplingPlanParams &params) {
    const ChannelMap channels = requested.resolved(first_pass);
    for (Role role : {Role::D1, Role::D2Min, Role::D2Max, Role::ObjectId, Role::PixelSize})
        if (!first_pass.has_channel(channels.channel(role)))
            throw InputError("missing sampling-plan input '" + std::string(role.key) + "' (channel " +
                             channels.channel(role) + ")");
    SamplingPlanInputs inputs;
    inputs.d1 = first_pass.channel(channels.channel(Role::D1));
    inputs.d2_min = first_pass.channel(channels.channel(Role::D2Min));
    inputs.d2_max = first_pass.channel(channels.channel(Role::D2Max));
    inputs.object_id = first_pass.channel(channels.channel(Role::ObjectId));
    inputs.pixel_size = first_pass.channel(channels.channel(Role::PixelSize));
    // The normal is optional: with it the plan uses the filter's projected footprint.
    const std::vector<std::string> &normal = channels.channels(Role::Normal);
    if (normal.size() == 3 && first_pass.has_channel(normal[0]) && first_pass.has_channel(normal[1]) &&
        first_pass.has_channel(normal[2]))
        for (std::size_t c = 0; c < 3; ++c) inputs.normal[c] = first_pass.channel(normal[c]);
    AovSet plan(first_pass.width(), first_pass.height());
    plan.attributes = first_pass.attributes;
    plan.attributes[attr::kAdaptiveMu] = aaf.mu;
    plan.attributes[attr::kMaxSpp] = params.max_spp;
    plan_samples(inputs, read_light_attributes(first_pass), aaf, params,
                 plan.add_channel(channels.channel(roles::PlannedSpp)));
    return plan;
}

}  // namespace aaf
