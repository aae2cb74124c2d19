#pragma once

#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/aov_set.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method.h"

namespace aaf::cli {

/// io::missing_input_recipes() for what `method` lacks in `aovs` (channels
/// found as `channels.resolved(aovs)` finds them), with the tracer's groups.
std::vector<std::string> missing_input_recipes(const Method &method, const AovSet &aovs,
                                               const ChannelMap &channels);

/// io::require_plan_inputs() with the tracer's groups: how `aaf filter` and
/// `aaf render --filter` name every missing input at once, before the method runs.
void require_plan_inputs(const FilterPlan &plan);

/// Throws aaf::InputError "no such channel 'X' (--map SPEC); did you mean
/// 'Y'?" for the first channel that a `--map` of `maps` names, `plan` reads
/// and `frame` (the frame `plan` was made for) lacks: a misspelt name is
/// named as such, not as a missing input.
void require_mapped_channels(const AovSet &frame, const std::vector<std::string> &maps,
                             const FilterPlan &plan);

}  // namespace aaf::cli
