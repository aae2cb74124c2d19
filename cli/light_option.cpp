#include "light_option.h"

#include "aaf/core/contract/aov_contract.h"
#include "aaf/trace/light_file.h"

namespace aaf::cli {

std::optional<std::map<std::string, AttributeValue>> light_option(const std::string &path) {
    if (path.empty()) return std::nullopt;
    AovSet holder(1, 1);  // write_light_attributes() writes into a set's header
    write_light_attributes(trace::load_light_file(path), holder);
    return holder.attributes;
}

bool apply_light_option(const std::optional<std::map<std::string, AttributeValue>> &light, AovSet &aovs) {
    if (!light) return false;
    bool had_own = false;
    for (const std::string &name : light_attribute_names()) had_own |= aovs.attributes.erase(name) > 0;
    for (const auto &entry : *light) aovs.attributes[entry.first] = entry.second;
    return had_own;
}

}  // namespace aaf::cli
