#pragma once

#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/core/framework/method.h"

namespace aaf {

/// What a method lacks to run on an AOV set.
struct MissingInputs {
    std::vector<Role> roles;              ///< required roles with a channel missing
    std::vector<std::string> attributes;  ///< required header attributes missing
    bool empty() const { return roles.empty() && attributes.empty(); }
};

/// The required roles and attributes of `method` that `aovs` lacks, with
/// the channels found as `channels.resolved(aovs)` finds them.
MissingInputs missing_inputs(const Method &method, const AovSet &aovs, const ChannelMap &channels);

/// The method that filters `aovs` when `method` is asked for, and its parameters.
struct MethodChoice {
    const Method *method = nullptr;
    ParameterSet parameters;
    /// Set when a delegate was chosen: "<why> (<its inputs>): filtered by
    /// <delegate> <its parameters>", for the user.
    std::string note;
};

/// The command line a delegate amounts to: "aaf filter maaf6 --pairs 1".
/// Throws aaf::Error when it names no registered method or parameter.
std::string delegate_command(const MethodDelegate &delegate);

/// Why `parameter` of `method` cannot be given for an input that `delegate`
/// filters: one line naming both methods and the parameter, the same for
/// `aaf filter` and `aaf render --filter`.
std::string delegate_parameter_refusal(const Method &method, const MethodDelegate &delegate,
                                       const std::string &parameter);

/// `method` with `parameters`, unless `aovs` lacks some of its required
/// inputs and has every input of one of its delegates (MethodInfo::delegates,
/// the first that can run): then that delegate at its defaults with the
/// delegate's fixed parameters. A delegate takes none of `method`'s
/// parameters, so choosing one while a parameter differs from its default
/// throws aaf::ParameterError (delegate_parameter_refusal()).
/// prepare_filter() plans with what this returns.
MethodChoice choose_method(const Method &method, const ParameterSet &parameters, const AovSet &aovs,
                           const ChannelMap &channels);

/// The channels `method` may read, as `channels` names them (resolve it
/// first): its required roles, the beauty, its optional roles. What a file
/// pipeline borrows from other parts and scrubs of NaN before filtering.
std::vector<std::string> method_input_channels(const Method &method, const ChannelMap &channels);

/// One frame's filter, prepared before it runs (OIDN's commit() before
/// execute()): the method chosen, its delegate resolved, the channels
/// mapped and the missing inputs listed, from the frame's channel names and
/// header attributes alone. Every consumer (filter_aovs(), the file
/// pipeline, the CLI, Python) runs the plan it prepared, so a frame's method
/// is chosen once and all of them agree on it.
struct FilterPlan {
    const Method *asked = nullptr;   ///< the method asked for
    const Method *method = nullptr;  ///< the one that runs: `asked`, or the delegate it hands the frame to
    ParameterSet parameters;         ///< `method`'s
    ChannelMap channels;             ///< role -> channel names, resolved against the frame
    MissingInputs missing;           ///< what `method` lacks in the frame; run_filter() refuses to run then
    /// choose_method()'s note when a delegate runs, for the user; else empty.
    std::string note;
    /// The channels `method` may read, its ratio roles' per-light layers
    /// included: what a pipeline borrows from a file's other parts and
    /// scrubs of NaN before the filter runs.
    std::vector<std::string> input_channels;
    bool reads_history = false;  ///< `method` reads the previous frame's output (Method::reads_history)
    Composition composition = Composition::Correct;  ///< how `method` makes the beauty
    bool ready() const { return method != nullptr && missing.empty(); }
};

/// The plan for filtering a frame with `method` and `parameters`: reads only
/// `frame`'s channel names and attributes, never its pixels. Throws
/// aaf::ParameterError as choose_method() does, aaf::InputError for a bad
/// attr::kRatioLights; a frame that lacks inputs gives a plan that lists
/// them (FilterPlan::missing) for the caller to report.
FilterPlan prepare_filter(const Method &method, const ParameterSet &parameters, const AovSet &frame,
                          const ChannelMap &channels, Composition composition = Composition::Correct);

/// The channels a plan for `frame` may read, whichever of `method` and its
/// delegates it runs, as `channels` names them in `frame` (per-light layers
/// included): what a file pipeline borrows from the file's other parts
/// before it prepares the plan on the completed frame.
std::vector<std::string> filter_input_candidates(const Method &method, const AovSet &frame,
                                                 const ChannelMap &channels);

/// Runs `plan` on `input`, the frame it was prepared for (with its pixels),
/// under filter_aovs()' output policy. Throws aaf::InputError naming the
/// first missing input when the plan is not ready, aaf::Error when `input`
/// lacks a channel the plan reads (a plan made for another frame), and as
/// filter_aovs() does.
AovSet run_filter(const FilterPlan &plan, const AovSet &input, const ProgressMonitor &monitor = {},
                  const AovSet *history = nullptr);
/// The same, taking the input's planes into the output instead of copying
/// them; `input` is left holding only the channels the output replaces.
AovSet run_filter(const FilterPlan &plan, AovSet &&input, const ProgressMonitor &monitor = {},
                  const AovSet *history = nullptr);

/// Runs `method` (or the delegate choose_method() picks) on an AOV set that follows the contract (other
/// renderers' names are found through the synonym table) and returns every input channel and attribute plus
/// the method's outputs. Output policy, the same for every method: channels the method writes replace earlier
/// ones of the same name rather than piling up beside them; outputs follow the kept inputs in the method's
/// declared order; when the method composes a new beauty, the input beauty is kept as Role::NoisyBeauty.
/// Throws aaf::InputError naming the first missing input or attribute, aaf::Error for bad parameters,
/// aaf::Cancelled when `monitor` asks to stop: run_filter(prepare_filter(...)). `history`, when given, is the
/// previous frame's output of the same method (MethodImages::history), of
/// the same size (else aaf::InputError).
AovSet filter_aovs(const Method &method, const AovSet &input, const ChannelMap &channels,
                   const ParameterSet &parameters, const ProgressMonitor &monitor = {},
                   const AovSet *history = nullptr);
/// The same, taking the input's planes into the output instead of copying
/// them (a frame less of peak memory); `input` is left holding only the
/// channels the output replaces.
AovSet filter_aovs(const Method &method, AovSet &&input, const ChannelMap &channels,
                   const ParameterSet &parameters, const ProgressMonitor &monitor = {},
                   const AovSet *history = nullptr);

}  // namespace aaf
