#include "aaf/io/filter_file.h"

#include <algorithm>
#include <memory>
#include <utility>

#include "aaf/core/error.h"
#include "aaf/core/filter_aovs.h"
#include "aaf/core/ratio_layers.h"
#include "aaf/core/thread_count.h"
#include "aaf/io/atomic_file.h"

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

/// A method that composes the beauty from the in-focus shadow drops the
/// input's defocus: say so, naming it, when the input was rendered through a lens.
void warn_if_defocused(const std::string &path, const AovSet &aovs, const FrameFilter &filter,
                       FilterFileReport &report) {
    if (filter.composes_beauty.empty()) return;
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

FrameFilter method_filter(const Method &method, const ParameterSet &parameters, const ChannelMap &channels) {
    FrameFilter filter;
    filter.input_channels = [&method, parameters, channels](const AovSet &input) {
        const ChannelMap found = channels.resolved(input);
        // The method that will run: `method` or the delegate it hands this input to.
        const Method &chosen = *choose_method(method, parameters, input, found).method;
        const MethodInfo &info = chosen.info();
        std::vector<std::string> names = method_input_channels(chosen, found);
        // The ratio roles' per-light layers are inputs too (ratio_layers.h).
        std::vector<Role> roles = info.roles.required;
        roles.insert(roles.end(), info.roles.optional.begin(), info.roles.optional.end());
        const int lights = ratio_light_count(input.attributes, input.channel_names().size());
        for (Role role : roles)
            if (is_per_light_role(role))
                for (int light = 0; light < lights; ++light)
                    for (const std::string &name : found.channels(role))
                        names.push_back(per_light_channel(name, light));
        return names;
    };
    // A method that reads the previous frame's output gets the last frame
    // this pipeline filtered (frames run in order, one at a time).
    auto history = std::make_shared<AovSet>();
    filter.reads_history = method.reads_history(parameters);
    filter.run = [&method, parameters, channels, history, keep = filter.reads_history](AovSet input) {
        const bool has_history = keep && history->pixel_count() > 0;
        AovSet output = filter_aovs(method, std::move(input), channels, parameters, {},
                                    has_history ? history.get() : nullptr);
        if (keep) *history = output;
        return output;
    };
    filter.forget_history = [history] { *history = AovSet(); };
    filter.note = [&method, parameters, channels](const AovSet &input) {
        return choose_method(method, parameters, input, channels).note;
    };
    const std::vector<Role> &outputs = method.info().roles.outputs;
    if (std::find(outputs.begin(), outputs.end(), Role::Beauty) != outputs.end())
        filter.composes_beauty = method.info().name;
    return filter;
}

AovSet filter_frame(AovSet input, const std::string &source, const FrameFilter &filter,
                    const FilterFileOptions &options, FilterFileReport &report) {
    if (filter.note) {
        const std::string note = with_context(source, [&] { return filter.note(input); });
        if (!note.empty()) report.notes.push_back(source + ": " + note);
    }
    warn_if_defocused(source, input, filter, report);
    if (options.replace_non_finite)
        report.non_finite = replace_non_finite(input, filter.input_channels(input));
    warn_if_non_finite(source, report);

    const ChannelMap resolved = options.channels.resolved(input);
    AovSet output;
    // The input moves into the filter, which moves its planes into the output: a lower peak of memory.
    run_with_threads(options.threads,
                     [&] { output = with_context(source, [&] { return filter.run(std::move(input)); }); });
    if (options.keep_beauty) output = keep_beauty(output, resolved);
    return output;
}

namespace {

/// filter_file() up to the write: the output and the input's `layout`.
AovSet read_and_filter(const std::string &input_path, const FrameFilter &filter,
                       const FilterFileOptions &options, FilterFileReport &report, ImageLayout &layout) {
    AovSet input = read_aovs(input_path, &layout);
    // AOVs the first part lacks may sit in other parts (one AOV per part);
    // they are read for the filter and stay in their parts in the output.
    // Scrubbing (in filter_frame) asks for the channels again: the borrowed
    // ones may complete a synonym.
    // Which channels depends on the input (a delegate's, choose_method()), which may refuse it: name the
    // file.
    const std::vector<std::string> wanted =
        with_context(input_path, [&] { return filter.input_channels(input); });
    report.borrowed = add_channels_from_other_parts(input_path, layout, wanted, input);
    AovSet output = filter_frame(std::move(input), input_path, filter, options, report);
    if (!report.borrowed.empty()) output = without_channels(output, report.borrowed);
    return output;
}

}  // namespace

AovSet filter_file_in_memory(const std::string &input_path, const FrameFilter &filter,
                             const FilterFileOptions &options, FilterFileReport &report) {
    ImageLayout layout;
    return read_and_filter(input_path, filter, options, report, layout);
}

FilterFileReport filter_file(const std::string &input_path, const std::string &output_path,
                             const FrameFilter &filter, const FilterFileOptions &options) {
    check_not_same_file(input_path, output_path);
    FilterFileReport report;
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
