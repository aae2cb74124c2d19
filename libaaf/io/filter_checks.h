#pragma once

#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/aov_set.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/filter_file.h"

namespace aaf::io {

/// Throws aaf::InputError "<path>: not an AOV EXR (<what it is>)" when
/// `frame`, read from `path` with `layout`, holds none of `wanted` (the
/// channels the filter may read) but the beauty, and no channel of any role
/// but the beauty as `channels` or the contract's own names find them (a
/// PNG, a beauty alone): nothing filters such a file, and its format and
/// channels say more than the list of every input a method lacks.
void require_aovs(const std::string &path, const AovSet &frame, const ImageLayout &layout,
                  const ChannelMap &channels, const std::vector<std::string> &wanted);

/// `channels` with the object id read from another channel when the one it
/// finds in `frame` holds a single value: a constant id tells no objects
/// apart, and at 0 (Blender's IndexOB with every pass index left at 0) it
/// makes every pixel background, which no method filters. The other channel
/// is the next one the role resolves to without it (the tracer's ids under
/// the view layer, as scripts/blender/aaf_complete.py adds them), when that
/// one is not constant too; else `channels` unchanged.
ChannelMap with_varying_object_id(const AovSet &frame, const ChannelMap &channels);

/// Reports into `report` (each message prefixed with `source`) an object id
/// that `plan` needs and that is constant in `input` (`channels` as the
/// pipeline was given them): a note naming the channel read instead
/// (with_varying_object_id()), or a warning with the fix when it is 0
/// everywhere and nothing replaced it. A constant non-zero id (one object
/// filling the frame) is fine.
void report_constant_object_id(const std::string &source, const AovSet &input, const FilterPlan &plan,
                               const ChannelMap &channels, FilterFileReport &report);

/// Warns (prefixed with `source`) for each pair the plan's method filters
/// (MethodRoles::filtered) whose output in `output` equals its input at
/// every pixel while the input is not constant: the filter ran but changed
/// nothing, a silent no-op the user must hear about.
void warn_if_unchanged(const std::string &source, const AovSet &output, const FilterPlan &plan,
                       FilterFileReport &report);

}  // namespace aaf::io
