#include "missing_input_report.h"

#include "aaf/io/missing_input_report.h"
#include "aaf/trace/render.h"
#include "suggestion.h"

namespace aaf::cli {

namespace {

/// The names of the `aaf render --aovs` groups that write `role`, comma-separated.
std::string groups_writing(Role role) {
    return trace::aov_groups_writing({role}).text();
}

}  // namespace

std::vector<std::string> missing_input_recipes(const Method &method, const AovSet &aovs,
                                               const ChannelMap &channels) {
    return io::missing_input_recipes(missing_inputs(method, aovs, channels), channels.resolved(aovs),
                                     groups_writing);
}

void require_plan_inputs(const FilterPlan &plan) {
    io::require_plan_inputs(plan, groups_writing);
}

void require_mapped_channels(const AovSet &frame, const std::vector<std::string> &maps,
                             const FilterPlan &plan) {
    for (const std::string &spec : maps) {
        ChannelMap map;
        map.set_override(spec);  // a bad spec was refused when the options were read
        const std::string key = spec.substr(0, spec.find('='));
        for (const RoleInfo &info : role_table()) {
            if (key != info.role.key) continue;
            for (const std::string &name : map.channels(info.role))
                if (!frame.has_channel(name) &&
                    std::find(plan.input_channels.begin(), plan.input_channels.end(), name) !=
                        plan.input_channels.end())
                    throw InputError("no such channel '" + name + "' (--map " + spec + ")" +
                                     did_you_mean(name, frame.channel_names()));
        }
    }
}

}  // namespace aaf::cli
