#include "aov_group.h"

#include <algorithm>
#include <sstream>

#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"
#include "aov_groups/aov_groups.h"

namespace aaf::trace {

void RenderState::for_each_row(int height, const std::function<void(int)> &row) {
    parallel_for_rows(height, row);
}

namespace {

/// Every registered group: how to make its accumulator, its declaration and
/// its parameters' defaults, in channel order.
struct Registry {
    std::vector<AovGroupRegistration::Maker> makers;
    std::vector<AovGroupInfo> table;
    std::vector<ParameterSet> defaults;
};

bool valid_name(const std::string &name, bool dash) {
    return !name.empty() && std::all_of(name.begin(), name.end(), [dash](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || (dash && c == '-');
    });
}

/// Checks `info` against the groups in `registry` and adds it.
void add_group(Registry &registry, AovGroupRegistration::Maker make) {
    AovGroupInfo info = make()->info();
    if (!valid_name(info.name, true) || info.name == "all")
        throw Error("AOV group name '" + info.name + "' must be lower-case letters, digits, _ or -, not all");
    for (const AovGroupInfo &existing : registry.table) {
        if (existing.name == info.name) throw Error("AOV group '" + info.name + "' is registered twice");
        for (const ParameterInfo &theirs : existing.parameters)
            for (const ParameterInfo &ours : info.parameters)
                if (theirs.name == ours.name)
                    throw Error("AOV group '" + info.name + "': parameter '" + ours.name +
                                "' is AOV group '" + existing.name + "''s too");
    }
    for (const ParameterInfo &parameter : info.parameters)
        if (!valid_name(parameter.name, false))
            throw Error("AOV group '" + info.name + "': parameter name '" + parameter.name +
                        "' must be lower-case letters, digits or _");
    registry.defaults.emplace_back(info.name, info.parameters);
    registry.makers.push_back(make);
    registry.table.push_back(std::move(info));
}

/// Built-ins first, on first use; a new built-in group adds one line here.
Registry &registry() {
    static Registry groups = [] {
        Registry builtin;
        for (AovGroupRegistration::Maker make : {
                 make_shadow_group,
                 make_position_group,
                 make_normal_group,
                 make_object_id_group,
                 make_unshadowed_group,
                 make_depth_group,
                 make_albedo_group,
                 make_motion_group,
                 make_progress_group,
                 make_maaf_group,
                 make_isg_group,
                 make_maaf6_group,
                 make_ratio_group,
                 make_ratio_estimators_group,
             })
            add_group(builtin, make);
        return builtin;
    }();
    return groups;
}

/// The index of group `name` in the registry, or -1.
int index_of(const std::string &name) {
    const std::vector<AovGroupInfo> &table = registry().table;
    for (std::size_t i = 0; i < table.size(); ++i)
        if (table[i].name == name) return int(i);
    return -1;
}

std::string group_names() {
    std::string known;
    for (const AovGroupInfo &info : registry().table) known += (known.empty() ? "" : ", ") + info.name;
    return known;
}

/// The index of group `name`; throws aaf::Error listing the known ones.
std::size_t checked_index(const std::string &name) {
    const int index = index_of(name);
    if (index < 0) throw Error("unknown AOV group '" + name + "' (groups: " + group_names() + ")");
    return std::size_t(index);
}

bool is_method(const std::string &name) {
    for (const Method *method : methods())
        if (method->info().name == name) return true;
    return false;
}

/// Whether `role` is a method's own (declared in its folder), not one several share.
bool is_methods_own_role(Role role) {
    const std::vector<RoleInfo> &shared = shared_roles();
    return std::none_of(shared.begin(), shared.end(),
                        [role](const RoleInfo &info) { return info.role == role; });
}

}  // namespace

AovGroupRegistration::AovGroupRegistration(Maker make) {
    add_group(registry(), make);
}

const std::vector<AovGroupInfo> &aov_group_table() {
    return registry().table;
}

const AovGroupInfo &find_aov_group(const std::string &name) {
    return registry().table[checked_index(name)];
}

AovGroups::AovGroups(std::initializer_list<std::string> names) {
    for (const std::string &name : names) insert(name);
}

AovGroups::AovGroups(const std::vector<std::string> &names) {
    for (const std::string &name : names) insert(name);
}

AovGroups AovGroups::every() {
    AovGroups groups;
    for (const AovGroupInfo &info : aov_group_table()) groups.names_.push_back(info.name);
    return groups;
}

bool AovGroups::contains(const std::string &group) const {
    return std::find(names_.begin(), names_.end(), group) != names_.end();
}

bool AovGroups::contains(const AovGroups &other) const {
    return std::all_of(other.names_.begin(), other.names_.end(),
                       [this](const std::string &name) { return contains(name); });
}

std::string AovGroups::text() const {
    std::string text;
    for (const std::string &name : names_) text += (text.empty() ? "" : ",") + name;
    return text;
}

AovGroups &AovGroups::insert(const std::string &group) {
    const std::size_t index = checked_index(group);
    if (contains(group)) return *this;
    // Before the first group that comes later in the registry.
    auto at = std::find_if(names_.begin(), names_.end(),
                           [index](const std::string &name) { return checked_index(name) > index; });
    names_.insert(at, group);
    return *this;
}

AovGroups &AovGroups::operator|=(const AovGroups &other) {
    for (const std::string &name : other.names_) insert(name);
    return *this;
}

AovGroups AovGroups::without(const AovGroups &other) const {
    AovGroups rest;
    for (const std::string &name : names_)
        if (!other.contains(name)) rest.names_.push_back(name);
    return rest;
}

const ParameterSet &AovGroupParameters::of(const std::string &group) const {
    const auto it = values_.find(group);
    return it != values_.end() ? it->second : registry().defaults[checked_index(group)];
}

ParameterSet &AovGroupParameters::of(const std::string &group) {
    const std::size_t index = checked_index(group);
    return values_.try_emplace(group, registry().defaults[index]).first->second;
}

std::vector<std::unique_ptr<AovAccumulator>> make_aov_accumulators(const AovGroups &groups,
                                                                   const AovGroupParameters &parameters) {
    std::vector<std::unique_ptr<AovAccumulator>> accumulators;
    accumulators.push_back(make_beauty_group());
    for (const std::string &name : groups.names()) {
        std::unique_ptr<AovAccumulator> group = registry().makers[checked_index(name)]();
        group->set_parameters(parameters.of(name));
        accumulators.push_back(std::move(group));
    }
    return accumulators;
}

std::vector<PlaneView> add_role_channels(AovSet &aovs, Role role, Precision precision) {
    std::vector<PlaneView> views;
    for (const std::string &name : role_info(role).channels) {
        views.push_back(aovs.add_channel(name));
        aovs.set_precision(name, precision);
    }
    return views;
}

AovGroups aov_groups_writing(const std::vector<Role> &roles) {
    AovGroups groups;
    for (const AovGroupInfo &info : aov_group_table())
        for (Role role : info.roles)
            if (std::find(roles.begin(), roles.end(), role) != roles.end()) groups.insert(info.name);
    return groups;
}

AovGroups aov_groups_for_method(const std::string &method) {
    const MethodRoles &roles = find_method(method).info().roles;
    std::vector<Role> written = roles.required;
    written.insert(written.end(), roles.rendered.begin(), roles.rendered.end());
    return aov_groups_writing(written);
}

AovGroups aov_groups_with_readers(const std::string &group) {
    AovGroups groups{group};
    std::vector<Role> own;
    for (Role role : find_aov_group(group).roles)
        if (is_methods_own_role(role)) own.push_back(role);
    for (const Method *method : methods()) {
        const std::vector<Role> &required = method->info().roles.required;
        if (std::any_of(required.begin(), required.end(),
                        [&own](Role role) { return std::find(own.begin(), own.end(), role) != own.end(); }))
            groups |= aov_groups_for_method(method->info().name);
    }
    return groups;
}

AovGroups parse_aov_groups(const std::string &list) {
    AovGroups groups;
    std::stringstream items(list);
    for (std::string item; std::getline(items, item, ',');) {
        if (is_method(item))
            groups |= aov_groups_for_method(item);
        else if (item == "all")
            groups |= AovGroups::every();
        else if (index_of(item) >= 0)
            groups |= aov_groups_with_readers(item);
        else {
            std::string known = "all";
            for (const Method *method : methods()) known += ", " + method->info().name;
            throw Error("unknown AOV group '" + item + "' (known: " + known + ", " + group_names() + ")");
        }
    }
    return groups;
}

std::string aov_groups_markdown() {
    std::string text =
        "| group (`--aovs`) | channels | roles | in `--aovs METHOD` for |\n| --- | --- | --- | --- |\n";
    for (const AovGroupInfo &group : aov_group_table()) {
        std::string roles, users;
        for (Role role : group.roles) roles += (roles.empty() ? "`" : ", `") + std::string(role.key) + "`";
        for (const Method *method : methods())
            if (aov_groups_for_method(method->info().name).contains(group.name))
                users += (users.empty() ? "`" : ", `") + method->info().name + "`";
        text += "| `" + group.name + "` | " + group.contents + " | " +
                (roles.empty() ? "- (tracer state)" : roles) + " | " + (users.empty() ? "-" : users) + " |\n";
    }
    return text;
}

}  // namespace aaf::trace
