#include "aaf/io/filter_file.h"

#include <algorithm>
#include <memory>
#include <utility>

#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/methods/maaf6/maaf6_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/io/atomic_file.h"
#include "filter_checks.h"

namespace aaf::io {

namespace {

bool contains(const std::vector<std::string> &names, const std::string &name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

/// A set with `aovs`' attributes and, in order, the channel `from` of each
/// (from, to) pair under the name `to` (values and storage precision copied).
AovSet with_channels(const AovSet &aovs, const std::vector<std::pair<std::string, std::string>> &from_to) {
    AovSet out(aovs.width(), aovs.height());
    out.attributes = aovs.attributes;
    for (const auto &[from, to] : from_to) {
        const std::size_t index = aovs.index_of(from);
        PlaneView plane = out.add_channel(to);
        std::copy(aovs.plane(index).begin(), aovs.plane(index).end(), plane.data);
        out.set_precision(to, aovs.precision(index));
    }
    return out;
}

/// The filter's output with the input beauty back in R,G,B (or the renderer's
/// beauty layer) and the filtered image as aaf.R/G/B.
AovSet keep_beauty(const AovSet &filtered, const ChannelMap &channels) {
    const std::vector<std::string> &beauty = channels.channels(Role::Beauty);
    const std::vector<std::string> &noisy = channels.channels(Role::NoisyBeauty);
    const std::vector<std::string> &result = channels.channels(Role::FilteredBeauty);
    std::vector<std::pair<std::string, std::string>> from_to;
    for (const std::string &name : filtered.channel_names())
        if (!contains(beauty, name) && !contains(noisy, name)) from_to.emplace_back(name, name);
    for (std::size_t c = 0; c < beauty.size(); ++c) {
        if (filtered.has_channel(noisy[c])) from_to.emplace_back(noisy[c], beauty[c]);
        from_to.emplace_back(beauty[c], result[c]);
    }
    return with_channels(filtered, from_to);
}

/// `aovs` less the channels in `dropped`.
AovSet without_channels(const AovSet &aovs, const std::vector<std::string> &dropped) {
    std::vector<std::pair<std::string, std::string>> from_to;
    for (const std::string &name : aovs.channel_names())
        if (!contains(dropped, name)) from_to.emplace_back(name, name);
    return with_channels(aovs, from_to);
}

/// A method that recomposes the beauty from the in-focus shadow (--compose
/// paper) drops the input's defocus: say so, naming it, when the input was
/// rendered through a lens. (Corrected, such a beauty is kept, with a note.)
void warn_if_defocused(const std::string &path, const AovSet &aovs, const FrameFilter &filter,
                       const FilterPlan &plan, FilterFileReport &report) {
    if (filter.composes_beauty.empty() || plan.composition != Composition::Paper) return;
    // A maaf6 render's layers are traced through the lens: its filter keeps the defocus.
    if (aovs.attributes.count(attr::kMaaf6Pairs)) return;
    auto it = aovs.attributes.find(attr::kApertureRadius);
    const float *aperture = it == aovs.attributes.end() ? nullptr : std::get_if<float>(&it->second);
    if (aperture && *aperture > 0)
        report.warnings.push_back(path + ": rendered through a thin lens; " + filter.composes_beauty +
                                  " filters the in-focus shadow, its output R,G,B has no defocus (aaf render "
                                  "--aovs maaf6 writes a combined-effects render, which keeps it)");
}

/// One warning per file that had NaN or infinite inputs, with the count per channel.
void warn_if_non_finite(const std::string &path, FilterFileReport &report) {
    if (report.non_finite.empty()) return;
    std::size_t total = 0;
    std::string detail;
    for (const auto &[name, count] : report.non_finite) {
        total += count;
        detail += (detail.empty() ? "" : ", ") + name + " " + std::to_string(count);
    }
    report.warnings.push_back(path + ": replaced " + std::to_string(total) + " NaN/Inf input values by 0 (" +
                              detail + ")");
}

}  // namespace

FrameFilter method_filter(const Method &method, const ParameterSet &parameters, const ChannelMap &channels,
                          Composition composition) {
    FrameFilter filter;
    filter.candidate_channels = [&method, channels](const AovSet &first_part) {
        return filter_input_candidates(method, first_part, channels);
    };
    filter.prepare = [&method, parameters, channels, composition](const AovSet &frame) {
        return prepare_filter(method, parameters, frame, with_varying_object_id(frame, channels),
                              composition);
    };
    // A method that reads the previous frame's output gets the last frame
    // this pipeline filtered (frames run in order, one at a time).
    auto history = std::make_shared<AovSet>();
    filter.reads_history = method.reads_history(parameters);
    filter.run = [history, keep = filter.reads_history](const FilterPlan &plan, AovSet input) {
        const bool has_history = keep && history->pixel_count() > 0;
        AovSet output = run_filter(plan, std::move(input), {}, has_history ? history.get() : nullptr);
        if (keep) *history = output;
        return output;
    };
    filter.forget_history = [history] { *history = AovSet(); };
    const std::vector<Role> &outputs = method.info().roles.outputs;
    if (std::find(outputs.begin(), outputs.end(), Role::Beauty) != outputs.end())
        filter.composes_beauty = method.info().name;
    return filter;
}

AovSet filter_frame(AovSet input, const FilterPlan &plan, const std::string &source,
                    const FrameFilter &filter, const FilterFileOptions &options, FilterFileReport &report) {
    if (!plan.note.empty()) report.notes.push_back(source + ": " + plan.note);
    report_constant_object_id(source, input, plan, options.channels, report);
    warn_if_defocused(source, input, filter, plan, report);
    if (options.replace_non_finite) report.non_finite = replace_non_finite(input, plan.input_channels);
    warn_if_non_finite(source, report);

    const ChannelMap resolved = options.channels.resolved(input);
    AovSet output;
    // The input moves into the filter, which moves its planes into the output: a lower peak of memory.
    run_with_threads(options.threads, [&] {
        output = with_context(source, [&] { return filter.run(plan, std::move(input)); });
    });
    warn_if_unchanged(source, output, plan, report);
    if (options.keep_beauty) output = keep_beauty(output, resolved);
    return output;
}

namespace {

/// filter_file() up to the write: the output and the input's `layout`.
AovSet read_and_filter(const std::string &input_path, const FrameFilter &filter,
                       const FilterFileOptions &options, FilterFileReport &report, ImageLayout &layout) {
    AovSet input = read_aovs(input_path, &layout);
    if (options.complete_header) options.complete_header(input);
    // AOVs the first part lacks may sit in other parts (one AOV per part);
    // they are read for the filter and stay in their parts in the output.
    // Which ones depends on the input (those of the method or of a
    // delegate), which may refuse it: name the file.
    if (filter.candidate_channels) {
        const std::vector<std::string> wanted =
            with_context(input_path, [&] { return filter.candidate_channels(input); });
        report.borrowed = add_channels_from_other_parts(input_path, layout, wanted, input);
        require_aovs(input_path, input, layout, options.channels, wanted);
    }
    // The frame is complete: its one plan decides what is scrubbed, noted and run.
    const FilterPlan plan =
        filter.prepare ? with_context(input_path, [&] { return filter.prepare(input); }) : FilterPlan{};
    AovSet output = filter_frame(std::move(input), plan, input_path, filter, options, report);
    if (!report.borrowed.empty()) output = without_channels(output, report.borrowed);
    return output;
}

}  // namespace

AovSet filter_file_in_memory(const std::string &input_path, const FrameFilter &filter,
                             const FilterFileOptions &options, FilterFileReport &report) {
    set_io_threads(options.threads);
    ImageLayout layout;
    return read_and_filter(input_path, filter, options, report, layout);
}

FilterFileReport filter_file(const std::string &input_path, const std::string &output_path,
                             const FrameFilter &filter, const FilterFileOptions &options) {
    check_not_same_file(input_path, output_path);
    FilterFileReport report;
    set_io_threads(options.threads);  // OpenEXR's (de)compression runs on as many threads as the filter
    // The input's header (every attribute, the windows) and its other parts
    // go through to the output unchanged.
    ImageLayout layout;
    AovSet output = read_and_filter(input_path, filter, options, report, layout);
    WriteOptions write = options.write;
    write.layout = &layout;
    write_aovs(output, output_path, write);
    return report;
}

}  // namespace aaf::io
