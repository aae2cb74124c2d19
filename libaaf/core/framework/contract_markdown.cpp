#include "aaf/core/framework/contract_markdown.h"

#include <cstdio>

#include <algorithm>
#include <vector>

#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"

namespace aaf {

namespace {

std::string code_list(const std::vector<std::string> &names, const char *separator = ", ") {
    std::string text;
    for (const std::string &name : names) text += (text.empty() ? "" : separator) + ("`" + name + "`");
    return text.empty() ? "-" : text;
}

std::string role_list(const std::vector<Role> &roles) {
    std::vector<std::string> keys;
    for (Role role : roles) keys.push_back(role.key);
    return code_list(keys);
}

bool has(const std::vector<Role> &roles, Role role) {
    return std::find(roles.begin(), roles.end(), role) != roles.end();
}

/// Names of the registered methods whose `roles_of` list holds `role`.
template <typename RolesOf>
std::vector<std::string> methods_with(Role role, const RolesOf &roles_of) {
    std::vector<std::string> names;
    for (const Method *method : methods())
        if (has(roles_of(method->info().roles), role)) names.push_back(method->info().name);
    return names;
}

}  // namespace

std::string roles_markdown() {
    std::string text =
        "| role (`--map` key) | default channels | units | meaning | read by | written by |\n"
        "| --- | --- | --- | --- | --- | --- |\n";
    for (const RoleInfo &info : role_table()) {
        std::vector<std::string> readers =
            methods_with(info.role, [](const MethodRoles &r) { return r.required; });
        for (const std::string &name :
             methods_with(info.role, [](const MethodRoles &r) { return r.optional; }))
            readers.push_back(name + " (optional)");
        const std::vector<std::string> writers =
            methods_with(info.role, [](const MethodRoles &r) { return r.outputs; });
        text += "| `" + std::string(info.role.key) + "` | " + code_list(info.channels) + " | " + info.units +
                " | " + info.meaning + " | " + code_list(readers) + " | " + code_list(writers) + " |\n";
    }
    return text;
}

std::string methods_markdown() {
    std::string text;
    for (const Method *method : methods()) {
        const MethodInfo &info = method->info();
        text += "### `aaf filter " + info.name + "`: " + info.summary + "\n\n";
        text += "Reference: " + info.reference + ".\n\n";
        text += "| reads | optional | writes | header attributes |\n| --- | --- | --- | --- |\n";
        text += "| " + role_list(info.roles.required) + " | " + role_list(info.roles.optional) + " | " +
                role_list(info.roles.outputs) + " | " + code_list(info.required_attributes) + " |\n\n";
        for (const MethodDelegate &delegate : info.delegates)
            text += "Given " + delegate.why + " (" + delegate.method +
                    "'s inputs rather than its own), it runs `" + delegate_command(delegate) + "`.\n\n";
        if (info.parameters.empty()) continue;
        text += "| parameter | default | unit | valid | meaning |\n| --- | --- | --- | --- | --- |\n";
        for (const ParameterInfo &p : info.parameters) {
            text += "| `" + p.option_name() + "` | " + p.default_value + " | " +
                    (p.unit.empty() ? "-" : p.unit) + " | " + p.range_text() + " | " + p.help + " |\n";
        }
        text += "\n";
    }
    return text;
}

std::string synonyms_markdown() {
    std::string text = "| role | tried, in order |\n| --- | --- |\n";
    for (const RoleInfo &info : role_table()) {
        std::string tried;
        for (const RoleSynonym &synonym : role_synonyms())
            if (synonym.role == info.role) {
                tried += (tried.empty() ? "" : "; ") + std::string(synonym.renderer) + " " +
                         code_list(synonym.channels);
                if (!synonym.scale.empty()) {
                    std::string factors;
                    for (float f : synonym.scale) {
                        char text[32];
                        std::snprintf(text, sizeof text, "%g", double(f));
                        factors += (factors.empty() ? "" : ", ") + std::string(text);
                    }
                    tried += " times (" + factors + ")";
                }
            }
        if (!tried.empty()) text += "| `" + std::string(info.role.key) + "` | " + tried + " |\n";
    }
    text +=
        "| every role, last | its contract names under the file's view-layer prefix (shared by every "
        "channel, no pass's layer): `ViewLayer.shadow.V`, ... |\n";
    return text;
}

}  // namespace aaf
