#include "missing_input_report.h"

#include <algorithm>

#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/util/error.h"
#include "aaf/trace/render.h"
#include "suggestion.h"

namespace aaf::cli {

namespace {

/// The names of the `aaf render --aovs` groups that write `role`, comma-separated.
std::string groups_writing(Role role) {
    return trace::aov_groups_writing({role}).text();
}

std::string joined(const std::vector<std::string> &names, const char *separator) {
    std::string text;
    for (const std::string &name : names) text += (text.empty() ? "" : separator) + name;
    return text;
}

}  // namespace

std::vector<std::string> missing_input_recipes(const Method &method, const AovSet &aovs,
                                               const ChannelMap &channels) {
    return missing_input_recipes(missing_inputs(method, aovs, channels), channels.resolved(aovs));
}

std::vector<std::string> missing_input_recipes(const MissingInputs &missing, const ChannelMap &found) {
    std::vector<std::string> recipes;
    for (Role role : missing.roles) {
        const RoleInfo &info = role_info(role);
        const std::string groups = groups_writing(role);
        recipes.push_back(std::string(info.role.key) + " [" + joined(found.channels(role), ",") + "]: " +
                          (groups.empty() ? "the beauty of any render"
                                          : "aaf render SCENE --aovs " + groups + " (exported shot)") +
                          ", or your renderer's pass with --map " + info.role.key +
                          "=CHANNEL (libaaf/RENDERERS.md)");
    }
    std::vector<std::string> light, other;
    const std::vector<std::string> &light_names = light_attribute_names();
    for (const std::string &name : missing.attributes)
        (std::find(light_names.begin(), light_names.end(), name) != light_names.end() ? light : other)
            .push_back(name);
    if (!light.empty())
        recipes.push_back("header " + joined(light, ",") +
                          ": --light LIGHT.json (the key light as a scene-format light object or scene "
                          "file; scripts/blender/aaf_bridge.py exports one)");
    if (!other.empty())
        recipes.push_back("header " + joined(other, ",") +
                          ": written by aaf render with the AOVs above (no option gives them)");
    return recipes;
}

std::string missing_inputs_message(const Method &method, const std::vector<std::string> &recipes) {
    return "missing " + std::to_string(recipes.size()) + " input" + (recipes.size() == 1 ? "" : "s") +
           " of " + method.info().title + ": " + joined(recipes, "; ");
}

void require_plan_inputs(const FilterPlan &plan) {
    const std::vector<std::string> recipes = missing_input_recipes(plan.missing, plan.channels);
    if (!recipes.empty()) throw InputError(missing_inputs_message(*plan.method, recipes));
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
