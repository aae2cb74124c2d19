#include <algorithm>

#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "builtin_methods.h"

namespace aaf {

namespace {

/// Owns every method; built-ins first, on first use.
std::vector<std::unique_ptr<Method>> &registry() {
    static std::vector<std::unique_ptr<Method>> methods = [] {
        std::vector<std::unique_ptr<Method>> builtin;
        builtin.push_back(make_aaf_method());         // Mehta et al. 2012
        builtin.push_back(make_gaussian_method());    // fixed-width baseline
        builtin.push_back(make_maaf_method());        // Wu et al. 2017
        builtin.push_back(make_isg_shadow_method());  // Robison, Shirley 2009
        builtin.push_back(make_isg_glossy_method());
        builtin.push_back(make_isg_dof_method());
        builtin.push_back(make_ratio_method());  // Heitz, Hill, McGuire 2018
        builtin.push_back(make_maaf6_method());  // Wu et al. 2017, Sec. 6.2
        return builtin;
    }();
    return methods;
}

std::vector<const Method *> &views() {
    static std::vector<const Method *> list;
    return list;
}

bool valid_role_key(const std::string &key) {
    return !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    });
}

bool valid_name(const std::string &name) {
    return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    });
}

/// The shared roles, then every method's declared ones, in registry order.
std::vector<RoleInfo> &all_roles() {
    static std::vector<RoleInfo> roles;
    return roles;
}

std::vector<RoleSynonym> &all_synonyms() {
    static std::vector<RoleSynonym> synonyms;
    return synonyms;
}

void check_declared_once(const std::vector<RoleInfo> &known, const MethodInfo &info) {
    for (std::size_t i = 0; i < info.roles.declared.size(); ++i) {
        const char *key = info.roles.declared[i].role.key;
        if (!valid_role_key(key))
            throw Error("method '" + info.name + "': role key '" + key + "' must be lower-case [a-z0-9_]");
        bool taken = std::any_of(known.begin(), known.end(),
                                 [&](const RoleInfo &r) { return r.role.key == std::string(key); });
        for (std::size_t j = 0; j < i; ++j)
            taken = taken || info.roles.declared[j].role.key == std::string(key);
        if (taken)
            throw Error("method '" + info.name + "' declares role '" + key + "', which is already declared");
    }
}

void refresh_views() {
    views().clear();
    all_roles() = shared_roles();
    all_synonyms() = shared_role_synonyms();
    for (const std::unique_ptr<Method> &m : registry()) {
        views().push_back(m.get());
        check_declared_once(all_roles(), m->info());
        const std::vector<RoleInfo> &declared = m->info().roles.declared;
        all_roles().insert(all_roles().end(), declared.begin(), declared.end());
        const std::vector<RoleSynonym> &synonyms = m->info().roles.synonyms;
        all_synonyms().insert(all_synonyms().end(), synonyms.begin(), synonyms.end());
    }
}

}  // namespace

const std::vector<const Method *> &methods() {
    if (views().size() != registry().size()) refresh_views();
    return views();
}

const std::vector<RoleInfo> &role_table() {
    methods();  // the built-in methods' roles join on first use
    return all_roles();
}

const std::vector<RoleSynonym> &role_synonyms() {
    methods();
    return all_synonyms();
}

const RoleInfo &role_info(Role role) {
    for (const RoleInfo &info : role_table())
        if (info.role == role) return info;
    throw Error(std::string("internal: role '") + role.key + "' is declared by no registered method");
}

const Method &find_method(const std::string &name) {
    std::string known;
    for (const Method *method : methods()) {
        if (method->info().name == name) return *method;
        known += (known.empty() ? "" : ", ") + method->info().name;
    }
    throw Error("unknown method '" + name + "' (methods: " + known + ")");
}

MethodRegistration::MethodRegistration(std::unique_ptr<Method> method) {
    const std::string &name = method->info().name;
    if (!valid_name(name))
        throw Error("method name '" + name + "' must be lower-case letters, digits, _ or -");
    for (const Method *existing : methods())
        if (existing->info().name == name) throw Error("method '" + name + "' is registered twice");
    check_declared_once(role_table(), method->info());
    registry().push_back(std::move(method));
    refresh_views();
}

}  // namespace aaf
