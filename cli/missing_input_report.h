#pragma once

#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/aov_set.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method.h"

namespace aaf::cli {

/// Every input `missing` lists, with the channels `found` names (a plan's
/// FilterPlan::missing and channels), each with how to produce it: a
/// role's channels and the `aaf render --aovs` group that writes them or the
/// `--map` line for another renderer's pass (libaaf/RENDERERS.md); the
/// missing `aaf:light:*` header attributes as one entry with `--light`, any
/// other missing header attributes (written by the tracer) as another.
/// Empty when nothing is missing.
std::vector<std::string> missing_input_recipes(const MissingInputs &missing, const ChannelMap &found);
/// The same for what `method` lacks in `aovs` (channels found as
/// `channels.resolved(aovs)` finds them).
std::vector<std::string> missing_input_recipes(const Method &method, const AovSet &aovs,
                                               const ChannelMap &channels);

/// The entries of missing_input_recipes() on one line, for an error message:
/// "missing N inputs of TITLE: a; b; ...".
std::string missing_inputs_message(const Method &method, const std::vector<std::string> &recipes);

/// Throws aaf::InputError with missing_inputs_message() when `plan` lacks
/// inputs: how `aaf filter` and `aaf render --filter` name every missing
/// input at once, with its recipe, before the method runs. A render made for
/// a delegate is checked as the delegate's (the plan's method).
void require_plan_inputs(const FilterPlan &plan);

/// Throws aaf::InputError "no such channel 'X' (--map SPEC); did you mean
/// 'Y'?" for the first channel that a `--map` of `maps` names, `plan` reads
/// and `frame` (the frame `plan` was made for) lacks: a misspelt name is
/// named as such, not as a missing input.
void require_mapped_channels(const AovSet &frame, const std::vector<std::string> &maps,
                             const FilterPlan &plan);

}  // namespace aaf::cli
