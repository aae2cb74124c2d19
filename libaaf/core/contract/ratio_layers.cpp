#include "aaf/core/contract/ratio_layers.h"

#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"

namespace aaf {

namespace {
/// A light's own layers hold at least its analytic U's R, G, B.
constexpr std::size_t kMinChannelsPerLight = 3;
}  // namespace

bool is_per_light_role(Role role) {
    return role_info(role).per_light;
}

std::string per_light_channel(const std::string &channel, int light) {
    const std::string tag = "L" + std::to_string(light) + ".";
    const std::string token = "ratio.";
    for (std::size_t at = channel.find(token); at != std::string::npos; at = channel.find(token, at + 1))
        if (at == 0 || channel[at - 1] == '.')
            return channel.substr(0, at + token.size()) + tag + channel.substr(at + token.size());
    const std::size_t last = channel.rfind('.');
    if (last == std::string::npos) return tag + channel;
    return channel.substr(0, last + 1) + tag + channel.substr(last + 1);
}

int ratio_light_count(const std::map<std::string, AttributeValue> &attributes, std::size_t channel_count) {
    const auto it = attributes.find(attr::kRatioLights);
    if (it == attributes.end()) return 0;
    const int *count = std::get_if<int>(&it->second);
    if (!count || *count < 0)
        throw InputError("header attribute " + quoted(attr::kRatioLights) + " must be a non-negative int");
    // Checked before anything is sized by it: a few header bytes must not
    // ask for millions of layer names.
    if (std::size_t(*count) * kMinChannelsPerLight > channel_count)
        throw InputError("header attribute " + quoted(attr::kRatioLights) + " is " + std::to_string(*count) +
                         ", but the file has " + std::to_string(channel_count) + " channels (each light's " +
                         "ratio.L<i>.* layers take at least " + std::to_string(kMinChannelsPerLight) + ")");
    return *count;
}

}  // namespace aaf
