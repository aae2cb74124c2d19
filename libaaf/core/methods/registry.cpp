#include <algorithm>

#include "aaf/core/error.h"
#include "aaf/core/method_registry.h"
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

void refresh_views() {
    views().clear();
    for (const std::unique_ptr<Method> &m : registry()) views().push_back(m.get());
}

bool valid_name(const std::string &name) {
    return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    });
}

}  // namespace

const std::vector<const Method *> &methods() {
    if (views().size() != registry().size()) refresh_views();
    return views();
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
    registry().push_back(std::move(method));
    refresh_views();
}

}  // namespace aaf
