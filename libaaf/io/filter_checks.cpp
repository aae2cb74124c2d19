#include "filter_checks.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>
#include <vector>

#include "aaf/core/util/error.h"

namespace aaf::io {

namespace {

/// The value every pixel of channel `name` holds; nullopt when they differ
/// (or one is NaN) or `aovs` lacks the channel.
std::optional<float> constant_value(const AovSet &aovs, const std::string &name) {
    const std::size_t index = aovs.index_of(name);
    if (index == std::string::npos || aovs.pixel_count() == 0) return std::nullopt;
    const AovSet::Plane &plane = aovs.plane(index);
    const float first = plane.front();
    if (!std::all_of(plane.begin(), plane.end(), [first](float v) { return v == first; }))
        return std::nullopt;
    return first;
}

/// "a 4x4 PNG image with channels R, G, B": what a file that is no AOV set is.
std::string image_description(const AovSet &frame, const ImageLayout &layout) {
    std::string format = layout.format_name();
    if (format == "openexr")
        format = "OpenEXR";
    else
        for (char &c : format) c = char(std::toupper(static_cast<unsigned char>(c)));
    const std::vector<std::string> &names = frame.channel_names();
    constexpr std::size_t kListed = 8;  // a long list would bury the point
    std::string listed;
    for (std::size_t c = 0; c < std::min(names.size(), kListed); ++c)
        listed += (listed.empty() ? "" : ", ") + names[c];
    if (names.size() > kListed) listed += ", ... (" + std::to_string(names.size()) + " channels)";
    return "a " + std::to_string(frame.width()) + "x" + std::to_string(frame.height()) + " " +
           (format.empty() ? std::string() : format + " ") + "image with channels " + listed +
           ", none of them an AOV of libaaf/AOV_CONTRACT.md";
}

bool needs_role(const FilterPlan &plan, Role role) {
    if (!plan.method) return false;
    const std::vector<Role> needed = plan.method->roles_needed(plan.parameters);
    return std::find(needed.begin(), needed.end(), role) != needed.end();
}

std::string joined(const std::vector<std::string> &names) {
    std::string text;
    for (const std::string &name : names) text += (text.empty() ? "" : ",") + name;
    return text;
}

}  // namespace

void require_aovs(const std::string &path, const AovSet &frame, const ImageLayout &layout,
                  const ChannelMap &channels, const std::vector<std::string> &wanted) {
    const std::vector<std::string> beauty = channels.resolved(frame).channels(Role::Beauty);
    for (const std::string &name : wanted)
        if (frame.has_channel(name) && std::find(beauty.begin(), beauty.end(), name) == beauty.end()) return;
    for (const ChannelMap &map : {channels.resolved(frame), ChannelMap().resolved(frame)})
        for (const RoleInfo &info : role_table()) {
            if (info.role == Role::Beauty) continue;  // any picture's R, G, B
            for (const std::string &name : map.channels(info.role))
                if (frame.has_channel(name)) return;
        }
    throw InputError(path + ": not an AOV EXR (" + image_description(frame, layout) + ")");
}

ChannelMap with_varying_object_id(const AovSet &frame, const ChannelMap &channels) {
    const std::string found = channels.resolved(frame).channel(Role::ObjectId);
    if (!constant_value(frame, found)) return channels;
    // The role resolved among the other channels' names (pixels are not needed).
    AovSet others(1, 1);
    for (const std::string &name : frame.channel_names())
        if (name != found) others.add_channel(name);
    const std::string next = channels.resolved(others).channel(Role::ObjectId);
    if (next == found || !frame.has_channel(next) || constant_value(frame, next) ||
        next.find_first_of(",=") != std::string::npos)  // not expressible as a mapping
        return channels;
    ChannelMap chosen = channels;
    chosen.set_override(std::string(Role::ObjectId.key) + "=" + next);
    return chosen;
}

void report_constant_object_id(const std::string &source, const AovSet &input, const FilterPlan &plan,
                               const ChannelMap &channels, FilterFileReport &report) {
    if (!needs_role(plan, Role::ObjectId)) return;
    const std::string found = channels.resolved(input).channel(Role::ObjectId);
    const std::optional<float> value = constant_value(input, found);
    if (!value) return;
    const std::string &read = plan.channels.channel(Role::ObjectId);
    std::ostringstream constant;
    constant << "object id channel '" << found << "' is " << *value << " everywhere";
    if (read != found) {
        report.notes.push_back(source + ": " + constant.str() + "; reading the object ids from '" + read +
                               "' instead");
        return;
    }
    if (*value != 0) return;
    report.warnings.push_back(
        source + ": " + constant.str() +
        ", so every pixel counts as background and nothing is filtered; set each object's pass index in "
        "Blender (Object Properties > Relations > Pass Index), add the tracer's ids "
        "(scripts/blender/aaf_complete.py) or name an id channel with --map object_id=CHANNEL");
}

void warn_if_unchanged(const std::string &source, const AovSet &output, const FilterPlan &plan,
                       FilterFileReport &report) {
    if (!plan.method) return;
    for (const auto &[from, to] : plan.method->info().roles.filtered) {
        const std::vector<std::string> &in = plan.channels.channels(from), &out = plan.channels.channels(to);
        bool unchanged = in.size() == out.size(), varying = false;
        for (std::size_t c = 0; unchanged && c < in.size(); ++c) {
            const std::size_t i = output.index_of(in[c]), o = output.index_of(out[c]);
            unchanged =
                i != std::string::npos && o != std::string::npos && output.plane(i) == output.plane(o);
            varying = varying || (unchanged && !constant_value(output, in[c]));
        }
        if (unchanged && varying)  // a constant's filtering is that constant: no news
            report.warnings.push_back(source + ": " + plan.method->info().title + " changed nothing: " +
                                      joined(out) + " equals " + joined(in) + " at every pixel");
    }
}

}  // namespace aaf::io
