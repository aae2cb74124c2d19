#include "aov_group.h"

#include <algorithm>
#include <sstream>

#include "aaf/core/error.h"
#include "aaf/core/method_registry.h"
#include "aov_groups/aov_groups.h"

namespace aaf::trace {

namespace {

/// Every group's maker, in channel order; a new group adds one line here.
using Maker = std::unique_ptr<AovAccumulator> (*)();
constexpr Maker kGroupMakers[] = {
    make_shadow_group,     make_position_group,
    make_normal_group,     make_object_id_group,
    make_unshadowed_group, make_depth_group,
    make_albedo_group,     make_motion_group,
    make_progress_group,   make_maaf_group,
    make_isg_group,        make_maaf6_group,
    make_ratio_group,      make_ratio_estimators_group,
};

bool is_method(const std::string &name) {
    for (const Method *method : methods())
        if (method->info().name == name) return true;
    return false;
}

}  // namespace

std::vector<std::unique_ptr<AovAccumulator>> make_aov_accumulators(unsigned groups) {
    std::vector<std::unique_ptr<AovAccumulator>> accumulators;
    accumulators.push_back(make_beauty_group());
    for (Maker make : kGroupMakers) {
        std::unique_ptr<AovAccumulator> group = make();
        if (groups & group->info().group) accumulators.push_back(std::move(group));
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

const std::vector<AovGroupInfo> &aov_group_table() {
    static const std::vector<AovGroupInfo> table = [] {
        std::vector<AovGroupInfo> infos;
        for (Maker make : kGroupMakers) infos.push_back(make()->info());
        return infos;
    }();
    return table;
}

unsigned aov_groups_writing(const std::vector<Role> &roles) {
    unsigned groups = 0;
    for (Maker make : kGroupMakers) {
        const std::unique_ptr<AovAccumulator> accumulator = make();
        for (Role role : accumulator->roles())
            if (std::find(roles.begin(), roles.end(), role) != roles.end())
                groups |= accumulator->info().group;
    }
    return groups;
}

unsigned aov_groups_for_method(const std::string &method) {
    return aov_groups_writing(find_method(method).info().roles.required);
}

unsigned parse_aov_groups(const std::string &list) {
    unsigned groups = 0;
    std::stringstream items(list);
    for (std::string item; std::getline(items, item, ',');) {
        if (is_method(item)) {
            groups |= aov_groups_for_method(item);
            continue;
        }
        if (item == "all") {
            groups |= kAovsAll;
            continue;
        }
        bool found = false;
        for (const AovGroupInfo &info : aov_group_table())
            if (item == info.name) {
                groups |= info.group;
                found = true;
            }
        if (!found) {
            std::string known = "all";
            for (const Method *method : methods()) known += ", " + method->info().name;
            for (const AovGroupInfo &info : aov_group_table()) known += std::string(", ") + info.name;
            throw Error("unknown AOV group '" + item + "' (known: " + known + ")");
        }
    }
    return groups;
}

std::string aov_groups_markdown() {
    std::string text =
        "| group (`--aovs`) | channels | roles | in `--aovs METHOD` for |\n| --- | --- | --- | --- |\n";
    for (Maker make : kGroupMakers) {
        const std::unique_ptr<AovAccumulator> group = make();
        std::string roles, users;
        for (Role role : group->roles())
            roles += (roles.empty() ? "`" : ", `") + std::string(role_info(role).key) + "`";
        for (const Method *method : methods())
            if (aov_groups_for_method(method->info().name) & group->info().group)
                users += (users.empty() ? "`" : ", `") + method->info().name + "`";
        text += "| `" + std::string(group->info().name) + "` | " + group->info().contents + " | " +
                (roles.empty() ? "- (tracer state)" : roles) + " | " + (users.empty() ? "-" : users) + " |\n";
    }
    return text;
}

}  // namespace aaf::trace
