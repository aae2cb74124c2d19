#pragma once

#include <functional>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method.h"

namespace aaf::io {

/// The `aaf render --aovs` groups that write `role`, comma-separated, or ""
/// when none does: the tracer's registry answers (trace::aov_groups_writing),
/// which io does not link, so the caller passes it.
using GroupsWriting = std::function<std::string(Role role)>;

/// Every input `missing` lists, with the channels `found` names (a plan's
/// FilterPlan::missing and channels), each with how to produce it: a
/// role's channels and the `aaf render --aovs` group that writes them or the
/// `--map` line for another renderer's pass (libaaf/RENDERERS.md); the
/// missing `aaf:light:*` header attributes as one entry with `--light`, any
/// other missing header attributes (written by the tracer) as another.
/// Empty when nothing is missing.
std::vector<std::string> missing_input_recipes(const MissingInputs &missing, const ChannelMap &found,
                                               const GroupsWriting &groups_writing);

/// The entries of missing_input_recipes() on one line, for an error message:
/// "missing N inputs of TITLE: a; b; ...".
std::string missing_inputs_message(const Method &method, const std::vector<std::string> &recipes);

/// Throws aaf::InputError with missing_inputs_message() when `plan` lacks
/// inputs: how `aaf filter`, `aaf render --filter` and the Python module name
/// every missing input at once, with its recipe, before the method runs. A
/// render made for a delegate is checked as the delegate's (the plan's method).
void require_plan_inputs(const FilterPlan &plan, const GroupsWriting &groups_writing);

}  // namespace aaf::io
