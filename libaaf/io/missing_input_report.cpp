#include "aaf/io/missing_input_report.h"

#include <algorithm>

#include "aaf/core/util/error.h"

namespace aaf::io {

namespace {

std::string joined(const std::vector<std::string> &names, const char *separator) {
    std::string text;
    for (const std::string &name : names) text += (text.empty() ? "" : separator) + name;
    return text;
}

}  // namespace

std::vector<std::string> missing_input_recipes(const MissingInputs &missing, const ChannelMap &found,
                                               const GroupsWriting &groups_writing) {
    std::vector<std::string> recipes;
    for (Role role : missing.roles) {
        const RoleInfo &info = role_info(role);
        const std::string groups = groups_writing ? groups_writing(role) : std::string();
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

void require_plan_inputs(const FilterPlan &plan, const GroupsWriting &groups_writing) {
    const std::vector<std::string> recipes =
        missing_input_recipes(plan.missing, plan.channels, groups_writing);
    if (!recipes.empty()) throw InputError(missing_inputs_message(*plan.method, recipes));
}

}  // namespace aaf::io
