#pragma once

#include <functional>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/aov_set.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method.h"
#include "aaf/core/util/non_finite.h"
#include "aaf/io/exr_io.h"

namespace aaf::io {

/// A filter method as the file pipeline sees it: which channels it may read,
/// the plan it makes for a frame and how it runs that plan on the frame in
/// memory. filter_file() knows nothing else about it.
struct FrameFilter {
    /// Channel names, as resolved in `first_part`, that a plan may read
    /// (filter_input_candidates()): borrowed from the file's other parts when
    /// the first part lacks them, before the plan is prepared; a file that
    /// then holds none of them but the beauty, nor any other role's channel,
    /// is refused as not an AOV EXR. Unset: none (and no such check).
    std::function<std::vector<std::string>(const AovSet &first_part)> candidate_channels;
    /// The frame's plan (prepare_filter()), made once per frame from its
    /// channel names and header attributes, after borrowing: its
    /// input_channels are scrubbed of NaN/Inf and its note is reported. The
    /// pipeline calls it with the frame's name as context.
    std::function<FilterPlan(const AovSet &frame)> prepare;
    /// Runs the plan on the frame it was made for: returns the full output set
    /// (the input channels kept, the beauty roles as aov_contract.h names
    /// them, plus the outputs). The input is its own (filter_file moves the
    /// frame in), so it may take the input's planes into the output instead
    /// of copying them.
    std::function<AovSet(const FilterPlan &plan, AovSet input)> run;
    /// The method's name when it composes a new beauty from the in-focus
    /// shadow (a defocused input's beauty then loses its defocus, which the
    /// pipeline warns about); empty when it leaves the beauty alone.
    std::string composes_beauty;
    /// True when `run` reads the previous frame's output (Method::reads_history):
    /// each run's output is kept as the next run's history.
    bool reads_history = false;
    /// Drops the kept output, so that the next run starts a sequence afresh.
    std::function<void()> forget_history;
};

/// The registered method `method` with `parameters` as the pipeline runs it:
/// it borrows filter_input_candidates(), prepares with prepare_filter() and
/// runs with run_filter() (filter_aovs.h), making the beauty as `composition`
/// says. An object-id channel that holds one value over the frame (Blender's
/// IndexOB with every pass index at 0) gives way to the next channel the role
/// resolves to, when there is one that varies (the tracer's ids that
/// scripts/blender/aaf_complete.py adds); filter_frame() says so. `method`
/// must outlive the result.
FrameFilter method_filter(const Method &method, const ParameterSet &parameters, const ChannelMap &channels,
                          Composition composition = Composition::Correct);

/// Every policy of the file pipeline; the defaults are `aaf filter`'s.
struct FilterFileOptions {
    /// Role -> channel names (resolved against each input): where keep_beauty
    /// finds the beauty, the kept noisy beauty and the filtered beauty.
    ChannelMap channels;
    /// false: R,G,B become the filtered image, the input's kept as noisy.R/G/B
    /// (as FrameFilter::run returns it). true: R,G,B stay the input's and the
    /// filtered image is added as the FilteredBeauty role (aaf.R/G/B).
    bool keep_beauty = false;
    /// Replace NaN and +-Inf in the plan's input_channels by 0 before the
    /// filter runs (counted in the report), so one bad value cannot spread.
    bool replace_non_finite = true;
    /// oneTBB workers FrameFilter::run gets, 0 = all; the output does not
    /// depend on it.
    int threads = 0;
    /// Completes a frame's header as read, before anything is borrowed or
    /// planned (the CLI's --light replaces the light attributes); unset: none.
    std::function<void(AovSet &frame)> complete_header;
    /// Compression and half storage of the output; its `layout` is ignored
    /// (the input's header and other parts are always carried over).
    WriteOptions write;
};

/// What filter_file() did besides writing the output.
struct FilterFileReport {
    /// Messages for the user that are not warnings, each "<input>: <note>":
    /// the input was handed to another method (FilterPlan::note), a
    /// constant object id was read from another channel.
    std::vector<std::string> notes;
    /// Messages for the user, each "<input>: <problem>", in the order found:
    /// an object id that is 0 everywhere (every pixel background), a
    /// thin-lens input (AAF's output has no defocus), NaN/Inf replaced, a
    /// filtered output equal to its varying input (the filter changed nothing).
    std::vector<std::string> warnings;
    /// NaN/Inf values replaced per input channel (only channels that had any).
    NonFiniteCounts non_finite;
    /// Channels read from other parts of the input for the filter; they stay
    /// in their own parts in the output.
    std::vector<std::string> borrowed;
};

/// Filters one frame in memory with the plan prepared for it
/// (FrameFilter::prepare), as filter_file() does between reading and
/// writing: reports `plan`'s note, warns (into `report`, each message
/// prefixed with `source`) of a constant object id, a thin-lens input and
/// NaN/Inf, scrubs them, runs `filter` under `options.threads` workers, warns
/// when it changed nothing and optionally keeps the beauty. `source` names the frame in messages and errors
/// (a file, or a scene for a render filtered before it is written). `options.write` and
/// `options.complete_header` are not used.
AovSet filter_frame(AovSet input, const FilterPlan &plan, const std::string &source,
                    const FrameFilter &filter, const FilterFileOptions &options, FilterFileReport &report);

/// What filter_file() would write for `input_path`, computed in memory and
/// not written (same reading, borrowing, scrubbing and filter): replaying a
/// frame brings a history-reading filter's kept output up to it. Throws as
/// filter_file() does.
AovSet filter_file_in_memory(const std::string &input_path, const FrameFilter &filter,
                             const FilterFileOptions &options, FilterFileReport &report);

/// Filters one frame, file to file: reads `input_path` with its layout (every
/// header attribute, the windows, the other parts), completes its header,
/// borrows the filter's candidate channels the first part lacks from the
/// other parts, prepares the frame's plan, scrubs NaN/Inf, runs
/// `filter` under `options.threads` workers, optionally keeps the beauty, and
/// writes `output_path` atomically (a temporary renamed into place) with the
/// input's layout. The input is never modified and a failure leaves no
/// output. Throws aaf::InputError "<file>: <problem>" for unreadable,
/// mismatched or unwritable files, a file that holds no AOV but a beauty
/// ("<file>: not an AOV EXR (a 64x64 PNG image with channels R, G, B, ...)")
/// and `output_path` naming the input, and
/// the filter's own aaf::Error (kind kept) prefixed with "<input_path>: ".
FilterFileReport filter_file(const std::string &input_path, const std::string &output_path,
                             const FrameFilter &filter, const FilterFileOptions &options = {});

}  // namespace aaf::io
