#include <map>
#include <memory>
#include <string>
#include <vector>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/filter_file.h"
#include "aaf/io/sequence.h"
#include "aaf/io/temporal_filter.h"
#include "channel_options.h"
#include "commands.h"
#include "frame_history.h"
#include "frame_runner.h"
#include "light_option.h"
#include "missing_input_report.h"
#include "parameter_options.h"
#include "provenance.h"

namespace aaf::cli {

namespace fs = std::filesystem;

namespace {

std::string role_keys(const std::vector<Role> &roles) {
    std::string text;
    for (Role role : roles) text += std::string(text.empty() ? "" : " ") + role.key;
    return text.empty() ? "-" : text;
}

/// "  aaf: reads ...; optional ...; writes ..." and a line per option, for
/// the filter command's help (`aaf filter aaf --help` has the shared options too).
std::string method_contract_line(const MethodInfo &method) {
    std::string text = "  " + method.name + ": reads " + role_keys(method.roles.required) + "; optional " +
                       role_keys(method.roles.optional) + "; writes " + role_keys(method.roles.outputs) +
                       "\n";
    for (const MethodDelegate &delegate : method.delegates)
        text += "    given " + delegate.why + " (" + delegate.method + "'s inputs) instead: runs `" +
                delegate_command(delegate) + "`\n";
    for (const ParameterInfo &p : method.parameters) {
        text += "    " + p.option_name();
        if (p.type != ParameterType::Bool)
            text += " " + p.range_text() + " (default " + p.default_value + ")";
        text += ": " + p.help + (p.unit.empty() ? "" : ", " + p.unit) + "\n";
    }
    return text;
}

/// Options every method's subcommand shares: files, sequences, output layout.
struct FilterOptions {
    std::string input, output, light;
    std::map<std::string, std::string> parameters;  ///< given on the command line, as text
    std::vector<std::string> maps;
    int threads = 0;
    std::string frames, progress = "auto";
    const CLI::Option *frames_option = nullptr;  ///< tells `--frames ''` from no --frames
    bool skip_existing = false, skip_bad_frames = false;
    bool replace_beauty = true;
    Composition composition = Composition::Correct;
    io::WriteOptions write;
    TemporalWindowSettings temporal;
};

void add_common_options(CLI::App &cmd, FilterOptions &options) {
    cmd.add_option("input", options.input, "Input EXR with the method's AOVs, or a sequence (shot.####.exr)")
        ->required();
    cmd.add_option("-o,--output", options.output, "Output EXR, or a sequence pattern for a sequence")
        ->required();
    options.frames_option =
        cmd.add_option("--frames", options.frames, "Frames of a sequence: 1-100, 1-100x2, 1-100:2, 1,5,7-9");
    cmd.add_option("--light", options.light,
                   "JSON file with the key light (a scene-format light object or a scene file): replaces "
                   "the input's aaf:light:* header, for renderers that write none");
    cmd.add_option("--progress", options.progress, "auto, lines, jsonl, openjd or none")
        ->capture_default_str();
    cmd.add_flag(
        "--skip-existing", options.skip_existing,
        "Skip frames whose output is complete and up to date: made by this aaf with these settings from "
        "inputs unchanged since (the provenance in its header); redo stale or partial ones");
    cmd.add_flag("--skip-bad-frames", options.skip_bad_frames,
                 "Report a failed frame and continue (the exit code is still non-zero)");
    cmd.add_flag("--replace-beauty,!--keep-beauty", options.replace_beauty,
                 "R,G,B become the filtered image, the input's kept as noisy.R/G/B (default); "
                 "--keep-beauty leaves R,G,B as they were and adds the filtered image as aaf.R/G/B");
    const std::map<std::string, Composition> compositions = {{"correct", Composition::Correct},
                                                             {"paper", Composition::Paper}};
    cmd.add_option("--compose", options.composition,
                   "How R,G,B are made: correct (default) replaces only what the method models in the input "
                   "beauty, keeping everything else the renderer wrote; paper recomposes them from the "
                   "method's inputs as its paper does (AAF Eq. 1: r(x) V(x) plus the other lights)")
        ->transform(CLI::CheckedTransformer(compositions, CLI::ignore_case))
        ->default_str("correct");
    add_write_options(cmd, options.write, "the output");
    add_map_and_threads_options(cmd, options.maps, options.threads);
    cmd.add_option("--temporal-window", options.temporal.radius_frames,
                   "On a sequence: blend each filtered frame with the K filtered frames before and after it "
                   "whose inputs exist, followed by the motion layer, rejecting other surfaces (position, "
                   "normal, object id) and changes of shading beyond the noise; 0 = each frame alone")
        ->check(CLI::Range(0, 16))
        ->capture_default_str();
    cmd.add_option("--temporal-tolerance", options.temporal.shading_tolerance,
                   "With --temporal-window: how far a neighbour's value may differ from the frame's own, in "
                   "robust noise scales of their difference over a 16-pixel tile, before it weighs less "
                   "(Gaussian weight): lower rejects more change and averages less noise")
        ->check(CLI::Range(0.1, 100.0))
        ->capture_default_str();
    cmd.add_flag("--temporal-causal", options.temporal.causal,
                 "With --temporal-window: only the frames before (a frame never waits for later ones)");
}

/// The method's parameters: defaults, then those given (a bad one is a usage error).
ParameterSet parameters_from(const Method &method, const std::map<std::string, std::string> &given) {
    ParameterSet parameters = method.default_parameters();
    for (const auto &entry : given) try {
            parameters.set(entry.first, entry.second);
        } catch (const Error &e) {
            // Named as typed (--seed), as CLI11 names the options it checks itself.
            std::string option = entry.first;
            for (const ParameterInfo &info : method.info().parameters)
                if (info.name == entry.first) option = info.option_name();
            throw UsageError(option + ": " + e.what());
        }
    try {
        method.check_parameters(parameters);  // values that do not go together
    } catch (const Error &e) {
        throw UsageError(e.what());
    }
    return parameters;
}

/// What the output records and --skip-existing compares: every setting that changes the pixels.
Provenance filter_provenance(const Method &method, const ParameterSet &parameters,
                             const FilterOptions &options) {
    Provenance provenance;
    provenance.method = method.info().name;
    for (const ParameterInfo &parameter : method.info().parameters)
        provenance.parameters += parameter.name + "=" + parameters.text(parameter.name) + " ";
    provenance.parameters += std::string("compose=") +
                             (options.composition == Composition::Paper ? "paper" : "correct") +
                             std::string(" keep_beauty=") + (options.replace_beauty ? "false" : "true") +
                             " half=" + (options.write.half_colour ? "true" : "false") +
                             " compression=" + options.write.compression;
    for (const std::string &map : options.maps) provenance.parameters += " map:" + map;
    if (options.temporal.radius_frames > 0)
        provenance.parameters += " temporal_window=" + std::to_string(options.temporal.radius_frames) +
                                 " temporal_tolerance=" + std::to_string(options.temporal.shading_tolerance) +
                                 (options.temporal.causal ? " temporal_causal=true" : "");
    return provenance;
}

/// `filter` as `aaf filter` runs it: a frame's plan that reads a channel a
/// `--map` of `maps` misspells, or that lacks inputs, is refused (the
/// channel and what it resembles; every missing input and its recipe)
/// before anything is scrubbed or run; each output is stamped with
/// `*current` (the frame being filtered).
void report_and_stamp(io::FrameFilter &filter, const std::vector<std::string> &maps,
                      const Provenance *const &current) {
    filter.prepare = [prepare = filter.prepare, maps](const AovSet &frame) {
        FilterPlan plan = prepare(frame);
        require_mapped_channels(frame, maps, plan);
        require_plan_inputs(plan);
        return plan;
    };
    filter.run = [&current, run = filter.run](const FilterPlan &plan, AovSet input) {
        AovSet output = run(plan, std::move(input));
        stamp(*current, output);
        return output;
    };
}

/// The file pipeline's policies as the options set them; --light completes each frame's header.
io::FilterFileOptions file_options(const FilterOptions &options, const ChannelMap &channels,
                                   const std::optional<std::map<std::string, AttributeValue>> &light) {
    io::FilterFileOptions file;
    if (light) file.complete_header = [light](AovSet &frame) { apply_light_option(light, frame); };
    file.channels = channels;
    file.keep_beauty = !options.replace_beauty;
    file.threads = options.threads;
    file.write = options.write;
    return file;
}

/// A frame's provenance under --temporal-window: its inputs hash covers every
/// input of its window and the first missing frame on each side (whose
/// appearance changes the window), and it records the frames read.
Provenance window_provenance(Provenance provenance, const std::string &pattern, int frame,
                             const TemporalWindowSettings &settings,
                             const std::function<std::vector<std::string>(const std::string &)> &own_inputs) {
    const std::vector<int> frames = io::temporal_window_frames(pattern, frame, settings);
    std::vector<std::string> files;
    for (int other : frames)
        for (const std::string &file : own_inputs(io::frame_path(pattern, other))) files.push_back(file);
    if (frames.front() > frame - settings.radius_frames)
        files.push_back(io::frame_path(pattern, frames.front() - 1));
    if (!settings.causal && frames.back() < frame + settings.radius_frames)
        files.push_back(io::frame_path(pattern, frames.back() + 1));
    provenance.inputs_hash = inputs_hash(files);
    if (frames.size() > 1)
        provenance.history = std::to_string(frames.front()) + "-" + std::to_string(frames.back());
    return provenance;
}

/// --temporal-window: `filter` blends each frame with its window; returns
/// the frame number the caller sets before each frame, or null without it.
std::shared_ptr<int> add_temporal_window(io::FrameFilter &filter, const FilterOptions &options,
                                         const io::FilterFileOptions &file) {
    if (options.temporal.radius_frames == 0) return nullptr;
    if (!io::is_sequence_pattern(options.input))
        throw UsageError("--temporal-window needs a sequence: an input pattern such as shot.####.exr");
    if (filter.reads_history)
        throw UsageError("--temporal-window and the method's --temporal are two temporal filters: use one");
    auto frame = std::make_shared<int>(0);
    filter = io::temporal_filter(filter, options.input, options.temporal, file, frame);
    return frame;
}

/// A method reading the previous frame's output (ratio --temporal): frame f's history is input
/// frame f - 1's output, back to the first of the run of consecutive frames on disk holding f.
FrameHistory::Source history_source(const std::string &pattern, io::FrameFilter &filter,
                                    const io::FilterFileOptions &file, const Provenance &provenance,
                                    const Provenance *&current,
                                    std::function<std::vector<std::string>(const std::string &)> own_inputs) {
    FrameHistory::Source source;
    source.continues = [pattern](int frame) {
        std::error_code error;
        return fs::exists(io::frame_path(pattern, frame - 1), error);
    };
    source.identity = [pattern, own_inputs](int frame, bool first) {
        std::vector<std::string> files = own_inputs(io::frame_path(pattern, frame));
        // The missing frame before the first: the sequence grows back if it appears.
        if (first) files.push_back(io::frame_path(pattern, frame - 1));
        return inputs_hash(files);
    };
    source.replay = [&filter, &file, &provenance, &current, pattern](int frame) {
        current = &provenance;         // stamped on an output that is not kept
        io::FilterFileReport ignored;  // its notes were given when it was filtered
        io::filter_file_in_memory(io::frame_path(pattern, frame), filter, file, ignored);
    };
    source.forget = [&filter] { filter.forget_history(); };
    return source;
}

void run_filter_command(const Method &method, const FilterOptions &options) {
    require_exr_output(options.output, "aaf filter");
    const ChannelMap channels = channel_map_from(options.maps);
    const auto light = light_option(options.light);
    const ParameterSet parameters = parameters_from(method, options.parameters);
    io::FrameFilter filter = io::method_filter(method, parameters, channels, options.composition);
    const Provenance provenance = filter_provenance(method, parameters, options);
    // The files a frame is made from, besides its history's or its window's.
    const std::function<std::vector<std::string>(const std::string &)> own_inputs =
        [&](const std::string &input) {
            std::vector<std::string> files{input};
            if (!options.light.empty()) files.push_back(options.light);
            return files;
        };
    std::optional<FrameHistory> history;
    const Provenance *current = nullptr;  // the frame being filtered
    const io::FilterFileOptions file = file_options(options, channels, light);
    const std::shared_ptr<int> window_frame = add_temporal_window(filter, options, file);
    const auto job_provenance = [&](const FrameJob &job) {
        Provenance p = provenance;
        if (window_frame) return window_provenance(p, options.input, job.frame, options.temporal, own_inputs);
        if (!history) {
            p.inputs_hash = inputs_hash(own_inputs(job.input));
            return p;
        }
        p.inputs_hash = history->chain_hash(job.frame);
        p.history = history->frames_read(job.frame);
        return p;
    };
    if (filter.reads_history && io::is_sequence_pattern(options.input))
        history.emplace(history_source(options.input, filter, file, provenance, current, own_inputs));
    report_and_stamp(filter, options.maps, current);
    RunOptions run;
    run.progress = progress_from_string(options.progress);
    run.skip_existing = options.skip_existing;
    run.up_to_date = [&](const FrameJob &job) { return output_up_to_date(job.output, job_provenance(job)); };
    run.skip_bad_frames = options.skip_bad_frames;
    const FrameJobs jobs =
        frame_jobs(options.input, options.output, given(options.frames_option, options.frames));
    // Frames stream one at a time (bounded memory); the filter itself runs on all threads.
    const std::size_t failed = run_frames(jobs, run, [&](const FrameJob &job) {
        const Provenance frame = job_provenance(job);
        if (history) history->prepare(job.frame);
        if (window_frame) *window_frame = job.frame;
        current = &frame;
        const io::FilterFileReport report = io::filter_file(job.input, job.output, filter, file);
        if (history) history->filtered(job.frame);
        for (const std::string &note : report.notes) std::fprintf(stderr, "aaf: note: %s\n", note.c_str());
        for (const std::string &warning : report.warnings)
            std::fprintf(stderr, "aaf: warning: %s\n", warning.c_str());
    });
    if (failed > 0)
        throw Error(std::to_string(failed) + " of " + std::to_string(jobs.size()) + " frames failed");
}

void add_method_command(CLI::App &filter, const Method &method) {
    auto options = std::make_shared<FilterOptions>();
    CLI::App *cmd = filter.add_subcommand(method.info().name, method.info().summary);
    add_common_options(*cmd, *options);
    add_parameter_options(*cmd, method.info().parameters, options->parameters);
    cmd->callback([options, &method] { run_filter_command(method, *options); });
}

}  // namespace

void add_filter_command(CLI::App &app) {
    CLI::App *filter = app.add_subcommand("filter", "Filter noisy AOVs with one of the methods");
    filter->require_subcommand(1);
    std::string contracts =
        "Methods, the roles each reads and writes (libaaf/AOV_CONTRACT.md; --map role=channel) and "
        "its options (aaf filter METHOD --help: every option):\n";
    for (const Method *method : methods()) {
        add_method_command(*filter, *method);
        contracts += method_contract_line(method->info());
    }
    filter->footer(contracts);
}

}  // namespace aaf::cli
