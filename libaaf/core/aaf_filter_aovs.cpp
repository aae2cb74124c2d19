#include <string>
#include <vector>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/error.h"

namespace aaf {

namespace {

std::array<ConstPlaneView, 3> channels3(const AovSet &aovs, const std::vector<std::string> &names) {
    return {aovs.channel(names[0]), aovs.channel(names[1]), aovs.channel(names[2])};
}

/// Copies every channel and attribute of `input`, leaving out `skip`.
AovSet copy_except(const AovSet &input, const std::vector<std::string> &skip) {
    AovSet out(input.width(), input.height());
    out.attributes = input.attributes;
    for (std::size_t c = 0; c < input.channel_names().size(); ++c) {
        const std::string &name = input.channel_names()[c];
        bool skipped = false;
        for (const std::string &s : skip) skipped = skipped || s == name;
        if (skipped) continue;
        PlaneView dst = out.add_channel(name);
        std::copy(input.plane(c).begin(), input.plane(c).end(), dst.data);
    }
    return out;
}

}  // namespace

AovSet aaf_filter_aovs(const AovSet &input, const ChannelMap &requested, const AafParams &params) {
    // Other renderers' names are found through the synonym table.
    const ChannelMap channels = requested.resolved(input);
    const MethodInputs &method = method_table().front();
    std::vector<Role> missing = channels.missing_inputs(method, input);
    if (!missing.empty()) {
        const RoleInfo &info = role_info(missing.front());
        std::string names;
        for (const std::string &name : channels.channels(info.role))
            names += (names.empty() ? "" : ",") + name;
        throw InputError("missing AAF input '" + std::string(info.key) + "' (channels " + names + ")");
    }
    const LightPlane light = read_light_attributes(input);

    AafInputs in;
    in.visibility = input.channel(channels.channel(Role::Visibility));
    in.d1 = input.channel(channels.channel(Role::D1));
    in.d2_min = input.channel(channels.channel(Role::D2Min));
    in.d2_max = input.channel(channels.channel(Role::D2Max));
    in.position = channels3(input, channels.channels(Role::Position));
    in.normal = channels3(input, channels.channels(Role::Normal));
    in.object_id = input.channel(channels.channel(Role::ObjectId));
    in.pixel_size = input.channel(channels.channel(Role::PixelSize));
    if (params.mu_from_spp) {
        const std::string &spp = channels.channel(Role::SamplesPerPixel);
        if (!input.has_channel(spp))
            throw InputError("mu from spp needs the 'spp' input (channel " + spp + ")");
        in.spp = input.channel(spp);
    }

    // Outputs replace earlier filter outputs rather than piling up beside them.
    const std::vector<std::string> &beauty = channels.channels(Role::Beauty);
    const std::vector<std::string> &noisy = channels.channels(Role::NoisyBeauty);
    std::vector<std::string> replaced = beauty;
    replaced.insert(replaced.end(), noisy.begin(), noisy.end());
    replaced.push_back(channels.channel(Role::FilteredVisibility));
    replaced.push_back(channels.channel(Role::FilterWidth));
    AovSet out = copy_except(input, replaced);

    AafOutputs result;
    result.filtered_visibility = out.add_channel(channels.channel(Role::FilteredVisibility));
    result.beta_m = out.add_channel(channels.channel(Role::FilterWidth));
    aaf_filter(in, light, params, result);

    // AAF Eq. 1: h(x) = r(x) times the (filtered) light-weighted visibility,
    // plus, when the renderer wrote it, the other lights' (unfiltered) shading.
    const std::vector<std::string> &unshadowed = channels.channels(Role::Unshadowed);
    const std::vector<std::string> &other_lights = channels.channels(Role::OtherLights);
    for (int c = 0; c < 3; ++c) {
        ConstPlaneView r = input.channel(unshadowed[c]);
        PlaneView filtered = out.add_channel(beauty[c]);
        for (int y = 0; y < input.height(); ++y)
            for (int x = 0; x < input.width(); ++x)
                filtered(x, y) = r(x, y) * result.filtered_visibility(x, y);
        if (input.has_channel(other_lights[c])) {
            ConstPlaneView other = input.channel(other_lights[c]);
            for (int y = 0; y < input.height(); ++y)
                for (int x = 0; x < input.width(); ++x) filtered(x, y) += other(x, y);
        }
        if (input.has_channel(beauty[c])) {
            ConstPlaneView noisy_in = input.channel(beauty[c]);
            PlaneView kept = out.add_channel(noisy[c]);
            for (int y = 0; y < input.height(); ++y)
                for (int x = 0; x < input.width(); ++x) kept(x, y) = noisy_in(x, y);
        }
    }
    return out;
}

}  // namespace aaf
