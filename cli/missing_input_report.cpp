#include "missing_input_report.h"

#include "aaf/io/missing_input_report.h"
#include "aaf/trace/render.h"

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

}  // namespace aaf::cli
