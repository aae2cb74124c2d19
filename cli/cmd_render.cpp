#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <utility>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/kernels/sample_statistics.h"
#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/filter_file.h"
#include "aaf/io/sequence.h"
#include "aaf/trace/render.h"
#include "channel_options.h"
#include "commands.h"
#include "frame_history.h"
#include "frame_runner.h"
#include "missing_input_report.h"
#include "parameter_options.h"
#include "provenance.h"

namespace aaf::cli {

namespace {

volatile std::sig_atomic_t interrupt_received = 0;

/// The first SIGINT/SIGTERM asks the render to stop after its current round
/// and write what it has; a second one kills as usual.
void on_interrupt(int signal) {
    interrupt_received = 1;
    std::signal(signal, SIG_DFL);
}

/// Reports a render's progress in the `--progress` mode: `auto` draws a bar
/// with the elapsed time and an ETA in place on a terminal (redrawn as the
/// tiles of each round finish, at most every 0.25 s) and, off a terminal,
/// writes a line at most every 10 % of the samples of a progressive render
/// (more than one round); `lines` writes a line at every 10 % and at least
/// every 2 s while tiles finish, whatever the render's size (stderr);
/// `jsonl` writes a "round" event per round and `openjd` an
/// `openjd_progress:` line per round of a progressive render (stdout,
/// beside the frame events). Called from the render's workers too: one call
/// at a time.
class RenderReporter {
  public:
    explicit RenderReporter(Progress mode)
        : mode_(mode), bar_(mode == Progress::Automatic && ::isatty(STDERR_FILENO)) {}

    /// After each round.
    void round(int done, int total) {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (mode_ == Progress::Jsonl || mode_ == Progress::OpenJd) {
            if (total <= trace::kSamplesPerRound) return;
            if (mode_ == Progress::Jsonl)
                std::cout << nlohmann::json{{"event", "round"},
                                            {"spp_done", done},
                                            {"spp", total},
                                            {"seconds", seconds()}}
                                 .dump()
                          << std::endl;
            else
                std::cout << "openjd_progress: " << 100.0 * done / total << std::endl;
            return;
        }
        if (mode_ == Progress::Automatic && !bar_ && total <= trace::kSamplesPerRound) return;
        show(done, total, /*force=*/true);
    }

    /// As the tiles of a round finish (a terminal's bar and `lines` only).
    void within_round(double done, int total) {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (bar_ || mode_ == Progress::Lines) show(done, total, /*force=*/false);
    }

  private:
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

    void show(double done, int total, bool force) {
        if (mode_ == Progress::None || total <= 0 || (shown_any_ && done <= shown_spp_)) return;
        const double elapsed = seconds();
        const int percent = int(100.0 * done / total);
        const double eta = done > 0 ? elapsed * (total - done) / done : 0;
        if (bar_) {
            if (!force && elapsed - shown_s_ < 0.25) return;
            const int filled = percent / 5;
            std::fprintf(stderr, "\rrender: [%-20s] %d/%d spp %.0f s, ETA %.0f s ",
                         std::string(std::size_t(filled), '#').c_str(), int(done), total, elapsed, eta);
            if (done >= total) std::fputc('\n', stderr);
        } else {
            const bool new_decile = percent / 10 != last_decile_;
            const bool due = mode_ == Progress::Lines && elapsed - shown_s_ >= 2.0;
            if (!new_decile && !due && done < total) return;
            if (!force && mode_ != Progress::Lines) return;
            std::fprintf(stderr, "render: %d/%d spp (%d%%) %.1f s, ETA %.1f s\n", int(done), total, percent,
                         elapsed, eta);
            last_decile_ = percent / 10;
        }
        shown_any_ = true;
        shown_spp_ = done;
        shown_s_ = elapsed;
        std::fflush(stderr);
    }

    Progress mode_;
    bool bar_;
    std::mutex mutex_;
    int last_decile_ = 0;
    bool shown_any_ = false;
    double shown_spp_ = 0, shown_s_ = 0;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// Checks the settings the command line gave as usage errors (exit 2), with
/// the library's ranges (trace::validate_render_settings).
void check_settings(const trace::RenderSettings &settings, bool resume) {
    try {
        trace::validate_render_settings(settings);
    } catch (const Error &e) {
        throw UsageError(e.what());
    }
    if (resume && settings.adaptive)
        throw UsageError("--resume continues a reference, not an adaptive render");
}

/// Refuses (aaf::InputError, exit 3) before anything renders an output that
/// is a file the scene reads (the JSON, an OBJ), under any name. A frame's
/// output can only be such a file if it exists, so for a sequence only the
/// frames on disk are looked at, whatever the range's length.
void check_outputs_spare_inputs(const std::string &scene, const std::string &output,
                                const std::optional<io::FrameRange> &frames) {
    const std::vector<std::string> inputs = trace::scene_input_files(scene);
    std::vector<std::string> outputs;
    const std::filesystem::path folder = std::filesystem::path(output).parent_path();
    if (!frames)
        outputs.push_back(output);
    else if (std::filesystem::is_directory(folder.empty() ? "." : folder))  // else no frame exists yet
        for (int frame : io::frames_on_disk(output))
            if (frames->contains(frame)) outputs.push_back(io::frame_path(output, frame));
    for (const std::string &input : inputs)
        for (const std::string &path : outputs) io::check_not_same_file(input, path);
}

/// Every setting of a render that changes its pixels, "name=value ...", for
/// its provenance (the frame included: a sequence's frames differ by it).
std::string render_parameters(const trace::RenderSettings &settings) {
    std::ostringstream text;
    text << "width=" << settings.width << " height=" << settings.height << " spp=" << settings.spp
         << " seed=" << trace::effective_seed(settings);
    // Only for a frame's mixed seed, so that earlier single renders stay up to date.
    if (settings.seed_per_frame) text << " base_seed=" << settings.seed;
    text << " frame=" << settings.frame << " aovs=" << settings.aovs.text()
         << " adaptive=" << settings.adaptive << " "
         << adaptive_parameters_text(settings.plan, settings.max_spp)
         << " light=" << (settings.light_profile ? to_string(*settings.light_profile) : "scene")
         << " falloff=" << settings.cosine_falloff << " skip_self_occluded=" << settings.skip_self_occluded;
    // The parameters of the groups rendered (AovGroupInfo::parameters), as declared.
    for (const std::string &group : settings.aovs.names())
        for (const ParameterInfo &parameter : trace::find_aov_group(group).parameters)
            text << " " << parameter.name << "=" << settings.group_parameters.of(group).text(parameter.name);
    return text.str();
}

/// `aaf render --filter METHOD --filter-param NAME=VALUE ...`: the method
/// that filters each frame before it is written, and its parameters.
struct RenderFilter {
    const Method *method = nullptr;
    ParameterSet parameters;
    /// Each --filter-param as given, with the parameter's declared name and value.
    struct Assignment {
        std::string text, name, value;
    };
    std::vector<Assignment> assignments;
};

/// The method named by --filter with its defaults and the --filter-param
/// values over them; an unknown method, a malformed NAME=VALUE or a bad
/// value is a usage error (exit 2), found before anything renders.
RenderFilter render_filter(const std::string &name, const std::vector<std::string> &assignments) {
    RenderFilter filter;
    try {
        filter.method = &find_method(name);
    } catch (const Error &e) {
        throw UsageError(std::string("--filter: ") + e.what());
    }
    filter.parameters = filter.method->default_parameters();
    for (const std::string &assignment : assignments) {
        const std::size_t equals = assignment.find('=');
        if (equals == std::string::npos || equals == 0)
            throw UsageError("--filter-param '" + assignment + "': expected NAME=VALUE (aaf filter " + name +
                             " --help lists the names)");
        // As `aaf filter METHOD --help` spells it (--normal-threshold) or as declared (normal_threshold).
        std::string parameter = assignment.substr(0, equals);
        if (parameter.rfind("--", 0) == 0) parameter.erase(0, 2);
        std::replace(parameter.begin(), parameter.end(), '-', '_');
        try {
            filter.parameters.set(parameter, assignment.substr(equals + 1));
        } catch (const Error &e) {
            throw UsageError("--filter-param '" + assignment + "': " + e.what());
        }
        filter.assignments.push_back({assignment, parameter, assignment.substr(equals + 1)});
    }
    try {
        filter.method->check_parameters(filter.parameters);  // values that do not go together
    } catch (const Error &e) {
        throw UsageError("--filter-param: " + std::string(e.what()));
    }
    return filter;
}

/// Refuses (UsageError) before anything renders a --filter whose parameters
/// make it read groups that `aovs` (given as `aovs_text`) does not render:
/// `--filter ratio --filter-param temporal=true` reads motion.
void check_parameter_groups(const RenderFilter &filter, const trace::AovGroups &aovs,
                            const std::string &aovs_text) {
    const Method &method = *filter.method;
    const trace::AovGroups missing =
        trace::aov_groups_writing(method.roles_needed(filter.parameters)).without(aovs);
    if (missing.empty()) return;
    // The assignments that ask for a missing group on their own, else all of them.
    std::string blamed;
    for (const RenderFilter::Assignment &assignment : filter.assignments) {
        ParameterSet alone = method.default_parameters();
        alone.set(assignment.name, assignment.value);
        try {
            // Some missing group is one this assignment reads.
            if (missing.without(trace::aov_groups_writing(method.roles_needed(alone))) != missing)
                blamed += (blamed.empty() ? "" : " ") + assignment.text;
        } catch (const Error &) {  // needs another assignment to be valid
        }
    }
    if (blamed.empty())
        for (const RenderFilter::Assignment &assignment : filter.assignments)
            blamed += (blamed.empty() ? "" : " ") + assignment.text;
    throw UsageError("--filter-param " + blamed + ": --filter " + method.info().name + " then reads the " +
                     missing.text() + " AOVs, which --aovs " + aovs_text +
                     " does not render (add them: --aovs " + aovs_text + "," + missing.text() +
                     ", or leave --aovs out)");
}

/// The filter's settings for the output's provenance, as `aaf filter` records
/// them but prefixed "filter." (a method may have a parameter named like a render setting).
std::string filter_parameters(const RenderFilter &filter) {
    std::string text = " filter=" + filter.method->info().name;
    for (const ParameterInfo &parameter : filter.method->info().parameters)
        text += " filter." + parameter.name + "=" + filter.parameters.text(parameter.name);
    return text;
}

/// The command line of `aaf render`, as parsed.
struct RenderOptions {
    std::string scene, output, light, aovs = "aaf", frames, resume, progress = "auto", filter;
    std::vector<std::string> filter_params;
    io::WriteOptions write;  ///< of complete frames; checkpoints keep the defaults, for --resume
    bool keep_beauty = false;
    GivenParameters plan;  ///< the adaptive plan's AAF parameters given
    trace::RenderSettings settings;
    /// The group parameters given (--maaf6-effects shadows): value by group and parameter name.
    std::map<std::pair<std::string, std::string>, std::string> group_values;
    double checkpoint_s = 60;
    bool list = false, skip_existing = false, timings = false, fixed_noise = false;
};

/// The scene, the output, the image and its samples, the AOV groups.
void add_image_options(CLI::App &cmd, RenderOptions &o) {
    cmd.add_option("scene", o.scene, "Scene file (.json) or built-in scene name (see --list)");
    cmd.add_option("-o,--output", o.output,
                   "Output EXR, or a sequence pattern (shot.####.exr) with --frames");
    cmd.add_option("--width", o.settings.width, "Image width, pixels")->capture_default_str();
    cmd.add_option("--height", o.settings.height, "Image height, pixels")->capture_default_str();
    cmd.add_option("--spp", o.settings.spp,
                   "Light samples per pixel, stratified over the light, in rounds of 1024")
        ->capture_default_str();
    cmd.add_option("--seed", o.settings.seed,
                   "Random seed; with --frames each frame draws with it mixed with the frame number "
                   "(header aaf:seed, the seed itself aaf:base_seed)")
        ->check(non_negative_seed())
        ->capture_default_str();
    cmd.add_flag("--fixed-noise", o.fixed_noise,
                 "With --frames: every frame draws with --seed itself, so a static shot's frames are "
                 "identical");
    cmd.add_option("--threads", o.settings.threads, "Worker threads, 0 = all (output is identical)")
        ->capture_default_str();
    cmd.add_option("--frame", o.settings.frame, "Animation time of a single render, frames")
        ->capture_default_str();
    cmd.add_option("--frames", o.frames, "Render a sequence: 1-24, 1-24x2, 1-24:2, 1,5,7-9");
    std::string groups, method_names;
    for (const trace::AovGroupInfo &group : trace::aov_group_table())
        groups += (groups.empty() ? "" : ", ") + group.name;
    for (const Method *method : methods())
        method_names += (method_names.empty() ? "" : ", ") + method->info().name;
    cmd.add_option("--aovs", o.aovs,
                   "AOVs beside the beauty, comma-separated: all (every group); a method (" + method_names +
                       "): the groups it reads; or a group (" + groups +
                       "): it and what the methods reading its own channels read. A name that is both is "
                       "the method's")
        ->capture_default_str();
}

/// One option per parameter a group declares (aov_group_registry.h), e.g.
/// --maaf6-effects; the values given land in `o.group_values`.
void add_group_options(CLI::App &cmd, RenderOptions &o) {
    for (const trace::AovGroupInfo &group : trace::aov_group_table())
        for (const ParameterInfo &parameter : group.parameters) {
            std::string help = "With --aovs " + group.name + ": " + parameter.help;
            if (!parameter.unit.empty()) help += "; " + parameter.unit;
            const auto key = std::make_pair(group.name, parameter.name);
            if (parameter.type == ParameterType::Bool) {
                cmd.add_flag_callback(
                    parameter.option_name(), [&o, key] { o.group_values[key] = "true"; }, help);
                continue;
            }
            const bool number =
                parameter.type == ParameterType::Int || parameter.type == ParameterType::Float;
            if (number || parameter.type == ParameterType::Choice) help += "; " + parameter.range_text();
            cmd.add_option_function<std::string>(
                   parameter.option_name(),
                   [&o, key](const std::string &value) { o.group_values[key] = value; }, help)
                ->type_name(parameter.type == ParameterType::Int     ? "INT"
                            : parameter.type == ParameterType::Float ? "FLOAT"
                                                                     : "TEXT")
                ->default_str(parameter.default_value);
        }
}

/// AAF's adaptive sampling, the lights, the self-occluded samples.
void add_sampling_options(CLI::App &cmd, RenderOptions &o) {
    cmd.add_flag("--adaptive", o.settings.adaptive,
                 "Two-pass adaptive sampling (AAF Sec. 6): --spp first, then AAF Eq. 21 per pixel");
    add_adaptive_options(cmd, o.plan, o.settings.max_spp);
    cmd.add_option("--light", o.light, "Override the lights' profile: gaussian or uniform")
        ->check(CLI::IsMember({"gaussian", "uniform"}));
    cmd.add_flag("--falloff", o.settings.cosine_falloff,
                 "Include the cosine falloff in the light function (AAF Sec. 7)");
    cmd.add_flag("--skip-self-occluded", o.settings.skip_self_occluded,
                 "Light samples behind the receiver's tangent plane give no occluder distance (the AAF "
                 "authors' code); by default they give an occluder at the receiver, d2 = d1");
}

/// Progressive rendering, sequences, the filter, the output's layout.
void add_run_options(CLI::App &cmd, RenderOptions &o) {
    cmd.add_option("--resume", o.resume,
                   "Continue a progressive render from this partial output (may be the -o file)");
    cmd.add_option("--checkpoint", o.checkpoint_s,
                   "Seconds between checkpoints of a progressive render (written to -o, resumable)")
        ->capture_default_str();
    cmd.add_option("--progress", o.progress,
                   "auto (a bar with an ETA on a terminal, else lines per 10 % of a progressive render), "
                   "lines (every 10 % and every 2 s), jsonl, openjd (per round of 1024 spp) or none; "
                   "per frame for a sequence")
        ->capture_default_str();
    cmd.add_flag(
        "--skip-existing", o.skip_existing,
        "Skip frames whose output is complete (all spp, not a checkpoint) and up to date: made by this "
        "aaf with these settings from the scene files unchanged since; redo stale or partial ones");
    cmd.add_option(
        "--filter", o.filter,
        "Filter each frame with this method (aaf filter METHOD) before writing it: one process, no "
        "intermediate file; --aovs defaults to the method's inputs");
    cmd.add_option("--filter-param", o.filter_params,
                   "NAME=VALUE: a parameter of the --filter method, named as its option in aaf filter METHOD "
                   "--help (normal-threshold=30) or as declared (normal_threshold=30); repeatable");
    cmd.add_flag(
        "--keep-beauty", o.keep_beauty,
        "With --filter: R,G,B stay the render's and the filtered image is added as aaf.R/G/B (as aaf "
        "filter --keep-beauty)");
    add_write_options(cmd, o.write, "a complete frame (a checkpoint stays float, zip:1)");
    cmd.add_flag("--timings", o.timings,
                 "Print each frame's timings on stderr (the render's passes, maaf6's sampling and "
                 "pre-filtering, the filter); they are never written into the output");
    cmd.add_flag("--list", o.list, "List the scenes found by name and exit");
}

/// The --filter method and the groups it makes the render write: with
/// --aovs left out, those the method and its parameters read; given, they
/// must include them (or a delegate's). Usage errors before anything renders.
std::optional<RenderFilter> resolve_filter(RenderOptions &o, const CLI::App &cmd) {
    trace::RenderSettings &settings = o.settings;
    if (o.filter.empty()) {
        if (!o.filter_params.empty()) throw UsageError("--filter-param needs --filter");
        if (o.keep_beauty) throw UsageError("--keep-beauty needs --filter");
        return std::nullopt;
    }
    RenderFilter filter = render_filter(o.filter, o.filter_params);
    const trace::AovGroups needed = trace::aov_groups_for_method(o.filter);
    // What the parameters add (--filter-param temporal=true: motion), decided before rendering.
    const trace::AovGroups with_parameters =
        needed | trace::aov_groups_writing(filter.method->roles_needed(filter.parameters));
    // A render for one of the method's delegates serves too: `--aovs maaf6 --filter aaf` runs
    // maaf6 --pairs 1 (choose_method), at the delegate's defaults.
    const MethodDelegate *served_by = nullptr;
    for (const MethodDelegate &delegate : filter.method->info().delegates)
        if (!served_by && settings.aovs.contains(trace::aov_groups_for_method(delegate.method)))
            served_by = &delegate;
    const bool own_inputs = settings.aovs.contains(needed);
    if (cmd.count("--aovs") == 0)
        settings.aovs = with_parameters;
    else if (own_inputs)
        check_parameter_groups(filter, settings.aovs, o.aovs);
    else if (!served_by)
        throw UsageError("--filter " + o.filter + " reads AOVs that --aovs " + o.aovs +
                         " does not render (add " + o.filter + " to --aovs, or leave --aovs out)");
    else if (!o.filter_params.empty()) {  // as `aaf filter` refuses it
        std::string name = o.filter_params.front().substr(0, o.filter_params.front().find('='));
        std::replace(name.begin(), name.end(), '-', '_');  // normal-threshold is normal_threshold
        throw UsageError(delegate_parameter_refusal(*filter.method, *served_by, name));
    }
    return filter;
}

/// Sets the group parameters given (before the settings are checked, which
/// asks each group about its own); a bad value is a usage error naming its option.
void set_group_parameters(RenderOptions &o) {
    for (const auto &[key, value] : o.group_values) {
        ParameterSet &values = o.settings.group_parameters.of(key.first);
        try {
            values.set(key.second, value);
        } catch (const Error &e) {
            throw UsageError(values.info(key.second).option_name() + ": " + e.what());
        }
    }
}

/// Warns of each option given that shapes nothing this render writes.
void warn_idle_options(const RenderOptions &o, const CLI::App &cmd) {
    // Options that only shape the adaptive second pass do nothing without it.
    if (!o.settings.adaptive)
        for (const std::string &option : adaptive_option_names())
            if (cmd.count(option) > 0)
                std::fprintf(stderr, "aaf: warning: %s has no effect without --adaptive\n", option.c_str());
    // Nor do a group's parameters without the group.
    for (const auto &entry : o.group_values) {
        const std::string &group = entry.first.first;
        if (o.settings.aovs.contains(group)) continue;
        const std::string option =
            o.settings.group_parameters.of(group).info(entry.first.second).option_name();
        std::fprintf(stderr, "aaf: warning: %s has no effect without the %s group (--aovs %s)\n",
                     option.c_str(), group.c_str(), group.c_str());
    }
}

/// The settings from the options, checked (usage errors, exit 2); the filter if any.
std::optional<RenderFilter> settings_from_options(RenderOptions &o, const CLI::App &cmd) {
    trace::RenderSettings &settings = o.settings;
    if (!o.light.empty()) settings.light_profile = light_profile_from_string(o.light);
    settings.plan = aaf_params_given(o.plan);
    try {
        settings.aovs = trace::parse_aov_groups(o.aovs);
    } catch (const Error &e) {
        throw UsageError(std::string("--aovs: ") + e.what());
    }
    std::optional<RenderFilter> filter = resolve_filter(o, cmd);
    set_group_parameters(o);
    check_settings(settings, !o.resume.empty());
    warn_idle_options(o, cmd);
    if (!(o.checkpoint_s > 0)) throw UsageError("--checkpoint must be positive");
    settings.checkpoint_interval_s = o.checkpoint_s;
    return filter;
}

/// One `aaf render` run over its frames: each frame's settings and
/// provenance, the --filter pipeline (and its history), the reports.
class RenderRun {
  public:
    RenderRun(const RenderOptions &o, std::optional<RenderFilter> filter, bool sequence, Progress progress)
        : o_(o),
          settings_(o.settings),
          sequence_(sequence),
          filter_(std::move(filter)),
          scene_hash_(inputs_hash(trace::scene_input_files(o.scene))),
          reporter_(sequence ? Progress::None : progress) {
        // One pipeline for the whole sequence: a method that reads the
        // previous frame's output gets it, as in `aaf filter`.
        if (filter_) {
            frame_filter_ =
                io::method_filter(*filter_->method, filter_->parameters, filter_options_.channels);
            filter_options_.threads = settings_.threads;
            filter_options_.keep_beauty = o.keep_beauty;
        }
        if (sequence_ && frame_filter_ && frame_filter_->reads_history) start_history();
    }

    Provenance provenance(const FrameJob &job) {
        trace::RenderSettings frame_settings = settings_;
        if (sequence_) frame_settings.frame = job.frame;
        std::string parameters = render_parameters(frame_settings);
        if (filter_) parameters += filter_parameters(*filter_);
        // Only where they differ from the defaults, so that earlier outputs stay up to date.
        if (o_.keep_beauty) parameters += " keep_beauty=true";
        if (o_.write.half_colour) parameters += " half=true";
        if (o_.write.compression != io::WriteOptions{}.compression)
            parameters += " compression=" + o_.write.compression;
        // Every frame renders the same scene files: its history adds only the frames it reads.
        return Provenance{"render", parameters, scene_hash_,
                          history_ ? history_->frames_read(job.frame) : ""};
    }

    /// Renders, filters and writes one frame.
    void render(const FrameJob &job) {
        if (interrupt_received) throw Interrupted{};  // the frames so far are complete
        trace::RenderSettings frame_settings = settings_of(job.frame);
        frame_settings.on_progress = [this](int done, int total) { reporter_.round(done, total); };
        frame_settings.on_round_progress = [this](double done, int total) {
            reporter_.within_round(done, total);
        };
        const Provenance stamped_by = provenance(job);
        frame_settings.on_checkpoint = [&](const AovSet &so_far) {
            AovSet stamped = so_far;
            stamp(stamped_by, stamped);
            io::write_aovs(stamped, job.output);
        };
        if (history_) history_->prepare(job.frame);
        trace::RenderTimings timings;
        // Scene and resume errors name their file themselves.
        AovSet aovs = trace::render_scene(job.input, frame_settings, &timings);
        const int done = std::get<int>(aovs.attributes.at(attr::kSppDone));
        // Statistics of the render, taken before the filter may replace its channels.
        const ChannelMap channels;
        const double mean_spp =
            settings_.adaptive ? mean_spp_over_shaded(aovs.channel(channels.channel(Role::SamplesPerPixel)),
                                                      aovs.channel(channels.channel(Role::ObjectId)))
                               : 0.0;
        double filter_s = 0;
        // An interrupted render is written unfiltered, so that --resume can continue it.
        if (frame_filter_ && done >= frame_settings.spp)
            filter_s = filter(aovs, job.input, /*report_notes=*/true);
        stamp(stamped_by, aovs);
        if (done < frame_settings.spp) {
            io::write_aovs(aovs, job.output);  // as a checkpoint: exact, for --resume
            std::fprintf(stderr,
                         "aaf: interrupted after %d of %d spp; %s holds them: continue with --resume %s\n",
                         done, frame_settings.spp, job.output.c_str(), job.output.c_str());
            throw Interrupted{};
        }
        io::write_aovs(aovs, job.output, o_.write);
        if (history_) history_->filtered(job.frame);
        report(job, timings, mean_spp, filter_s);
    }

  private:
    trace::RenderSettings settings_of(int frame) const {
        trace::RenderSettings frame_settings = settings_;
        if (sequence_) frame_settings.frame = frame;
        frame_settings.stop_requested = [] { return interrupt_received != 0; };
        return frame_settings;
    }

    /// Filters a complete render in memory; returns the seconds it took.
    double filter(AovSet &aovs, const std::string &source, bool report_notes) {
        const FilterPlan plan = frame_filter_->prepare(aovs);
        require_plan_inputs(plan);
        const auto start = std::chrono::steady_clock::now();
        io::FilterFileReport report;
        aovs = io::filter_frame(std::move(aovs), plan, source, *frame_filter_, filter_options_, report);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!report_notes) return seconds;
        for (const std::string &note : report.notes) std::fprintf(stderr, "aaf: note: %s\n", note.c_str());
        for (const std::string &warning : report.warnings)
            std::fprintf(stderr, "aaf: warning: %s\n", warning.c_str());
        return seconds;
    }

    /// A filter that reads the previous frame's output (ratio --temporal):
    /// frame f's history is frame f - 1's, back to the sequence's start, the
    /// scene's first key frame (frame 1 without animation), whatever frames
    /// this run renders.
    void start_history() {
        const std::optional<double> first_key = trace::scene_first_key_frame(o_.scene);
        const double start_frame = first_key ? std::floor(*first_key) : 1.0;
        FrameHistory::Source source;
        source.sequence_start = [start_frame](int frame) {
            return double(frame) <= start_frame ? frame : int(start_frame);
        };
        source.identity = [](int, bool) { return std::string(); };  // the scene hash covers it
        source.replay = [this](int frame) {
            AovSet aovs = trace::render_scene(o_.scene, settings_of(frame));
            if (std::get<int>(aovs.attributes.at(attr::kSppDone)) < settings_.spp) throw Interrupted{};
            filter(aovs, o_.scene, /*report_notes=*/false);
        };
        source.forget = [this] { frame_filter_->forget_history(); };
        history_.emplace(std::move(source));
    }

    void report(const FrameJob &job, const trace::RenderTimings &timings, double mean_spp,
                double filter_s) const {
        if (settings_.adaptive) {
            std::printf(
                "adaptive sampling: average %.2f spp over shaded pixels; first pass %.3f s, "
                "plan %.3f s, second pass %.3f s",
                mean_spp, timings.first_pass_s, timings.plan_s, timings.second_pass_s);
            if (frame_filter_) std::printf(", filter %.3f s", filter_s);
            std::printf("\n");
        }
        if (!o_.timings) return;
        std::fprintf(stderr, "aaf: timings: %s: light passes %.3f s", job.output.c_str(),
                     timings.first_pass_s + timings.plan_s + timings.second_pass_s);
        if (settings_.aovs.contains("maaf6"))
            std::fprintf(stderr, ", maaf6 sampling %.3f s, pre-filtering %.3f s", timings.maaf6_sampling_s,
                         timings.maaf6_prefilter_s);
        if (frame_filter_) std::fprintf(stderr, ", filter %.3f s", filter_s);
        std::fprintf(stderr, "\n");
    }

    const RenderOptions &o_;
    const trace::RenderSettings &settings_;
    bool sequence_;
    std::optional<RenderFilter> filter_;
    std::string scene_hash_;
    std::optional<io::FrameFilter> frame_filter_;
    io::FilterFileOptions filter_options_;
    std::optional<FrameHistory> history_;
    RenderReporter reporter_;
};

/// The command's callback: parses, renders every frame, reports.
void run_render_command(RenderOptions &o, const CLI::App &cmd) {
    if (o.list) {
        for (const std::string &name : trace::builtin_scene_names()) std::cout << name << "\n";
        return;
    }
    if (o.scene.empty()) throw CLI::RequiredError("scene");
    if (o.output.empty()) throw CLI::RequiredError("--output");
    require_exr_output(o.output, "aaf render");
    std::optional<RenderFilter> filter = settings_from_options(o, cmd);

    // An empty --frames would otherwise mean a single render.
    if (cmd.count("--frames") > 0 && o.frames.empty())
        throw UsageError("--frames: empty frame range (e.g. 1-24)");
    const bool sequence = !o.frames.empty();
    if (sequence != io::is_sequence_pattern(o.output))
        throw UsageError(sequence ? "--frames needs an output pattern such as shot.####.exr"
                                  : "an output pattern needs --frames");
    // A sequence's frames get independent noise; a single render keeps --seed.
    o.settings.seed_per_frame = sequence && !o.fixed_noise;
    if (o.fixed_noise && !sequence)
        std::fprintf(stderr, "aaf: warning: --fixed-noise has no effect without --frames\n");
    if (sequence && !o.resume.empty()) throw UsageError("--resume continues a single render, not a sequence");

    // Frames are produced as they come: `--frames 1-2000000000` costs one job's memory.
    std::optional<io::FrameRange> frames;
    if (sequence) frames = sequence_frames(o.output, o.frames);
    check_outputs_spare_inputs(o.scene, o.output, frames);
    const FrameJobs jobs = frames ? FrameJobs(FrameJobs::fixed_input(o.scene), o.output, *frames)
                                  : FrameJobs({{0, o.scene, o.output}});
    std::optional<AovSet> partial;
    if (!o.resume.empty()) {
        partial = io::read_aovs(o.resume);
        o.settings.resume = &*partial;
        o.settings.resume_source = o.resume;
    }
    RunOptions run;
    run.progress = progress_from_string(o.progress);
    run.skip_existing = o.skip_existing;
    RenderRun render(o, std::move(filter), sequence, run.progress);
    run.up_to_date = [&](const FrameJob &job) {
        return output_up_to_date(job.output, render.provenance(job));
    };
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    const std::size_t failed = run_frames(jobs, run, [&](const FrameJob &job) { render.render(job); });
    if (failed > 0)
        throw Error(std::to_string(failed) + " of " + std::to_string(jobs.size()) + " frames failed");
}

}  // namespace

void add_render_command(CLI::App &app) {
    auto options = std::make_shared<RenderOptions>();
    CLI::App *cmd = app.add_subcommand(
        "render", "Render a scene (JSON file or built-in name) to a multi-layer EXR of AOVs");
    add_image_options(*cmd, *options);
    add_group_options(*cmd, *options);
    add_sampling_options(*cmd, *options);
    add_run_options(*cmd, *options);
    cmd->callback([options, cmd] { run_render_command(*options, *cmd); });
}

}  // namespace aaf::cli
