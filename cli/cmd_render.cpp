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
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/core/filter_aovs.h"
#include "aaf/core/method_registry.h"
#include "aaf/core/sample_statistics.h"
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
         << " seed=" << settings.seed << " frame=" << settings.frame << " aovs=" << settings.aovs
         << " adaptive=" << settings.adaptive << " "
         << adaptive_parameters_text(settings.plan, settings.max_spp)
         << " light=" << (settings.light_profile ? to_string(*settings.light_profile) : "scene")
         << " falloff=" << settings.cosine_falloff << " skip_self_occluded=" << settings.skip_self_occluded
         << " maaf_first_pass_spp=" << settings.maaf_first_pass_spp;
    if (settings.aovs & trace::kAovMaaf6) text << " maaf6_effects=" << settings.maaf6_effects;
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

/// The `--aovs` names of `groups`, comma-separated.
std::string group_names(unsigned groups) {
    std::string names;
    for (const trace::AovGroupInfo &group : trace::aov_group_table())
        if (group.group & groups) names += (names.empty() ? "" : ",") + std::string(group.name);
    return names;
}

/// Refuses (UsageError) before anything renders a --filter whose parameters
/// make it read groups that `aovs` (given as `aovs_text`) does not render:
/// `--filter ratio --filter-param temporal=true` reads motion.
void check_parameter_groups(const RenderFilter &filter, unsigned aovs, const std::string &aovs_text) {
    const Method &method = *filter.method;
    const unsigned missing = trace::aov_groups_writing(method.roles_needed(filter.parameters)) & ~aovs;
    if (missing == 0) return;
    // The assignments that ask for a missing group on their own, else all of them.
    std::string blamed;
    for (const RenderFilter::Assignment &assignment : filter.assignments) {
        ParameterSet alone = method.default_parameters();
        alone.set(assignment.name, assignment.value);
        try {
            if (trace::aov_groups_writing(method.roles_needed(alone)) & missing)
                blamed += (blamed.empty() ? "" : " ") + assignment.text;
        } catch (const Error &) {  // needs another assignment to be valid
        }
    }
    if (blamed.empty())
        for (const RenderFilter::Assignment &assignment : filter.assignments)
            blamed += (blamed.empty() ? "" : " ") + assignment.text;
    throw UsageError("--filter-param " + blamed + ": --filter " + method.info().name + " then reads the " +
                     group_names(missing) + " AOVs, which --aovs " + aovs_text +
                     " does not render (add them: --aovs " + aovs_text + "," + group_names(missing) +
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

}  // namespace

void add_render_command(CLI::App &app) {
    struct Options {
        std::string scene, output, light, aovs = "aaf", frames, resume, progress = "auto", filter;
        std::vector<std::string> filter_params;
        io::WriteOptions write;  ///< of complete frames; checkpoints keep the defaults, for --resume
        bool keep_beauty = false;
        GivenParameters plan;  ///< the adaptive plan's AAF parameters given
        trace::RenderSettings settings;
        double checkpoint_s = 60;
        bool list = false, skip_existing = false, timings = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand(
        "render", "Render a scene (JSON file or built-in name) to a multi-layer EXR of AOVs");
    cmd->add_option("scene", options->scene, "Scene file (.json) or built-in scene name (see --list)");
    cmd->add_option("-o,--output", options->output,
                    "Output EXR, or a sequence pattern (shot.####.exr) with --frames");
    cmd->add_option("--width", options->settings.width, "Image width, pixels")->capture_default_str();
    cmd->add_option("--height", options->settings.height, "Image height, pixels")->capture_default_str();
    cmd->add_option("--spp", options->settings.spp,
                    "Light samples per pixel, stratified over the light, in rounds of 1024")
        ->capture_default_str();
    cmd->add_option("--seed", options->settings.seed, "Random seed")
        ->check(non_negative_seed())
        ->capture_default_str();
    cmd->add_option("--threads", options->settings.threads, "Worker threads, 0 = all (output is identical)")
        ->capture_default_str();
    cmd->add_option("--frame", options->settings.frame, "Animation time of a single render, frames")
        ->capture_default_str();
    cmd->add_option("--frames", options->frames, "Render a sequence: 1-24, 1-24x2, 1-24:2, 1,5,7-9");
    cmd->add_option("--aovs", options->aovs,
                    "AOV groups, comma-separated: aaf (default), all, shadow, position, normal, id, "
                    "unshadowed, depth, albedo, motion, progress")
        ->capture_default_str();
    cmd->add_option("--maaf6-effects", options->settings.maaf6_effects,
                    "With --aovs maaf6: the effects its path samples trace, any of defocus,shadows,indirect")
        ->capture_default_str();
    cmd->add_flag("--adaptive", options->settings.adaptive,
                  "Two-pass adaptive sampling (AAF Sec. 6): --spp first, then AAF Eq. 21 per pixel");
    add_adaptive_options(*cmd, options->plan, options->settings.max_spp);
    cmd->add_option("--light", options->light, "Override the lights' profile: gaussian or uniform")
        ->check(CLI::IsMember({"gaussian", "uniform"}));
    cmd->add_flag("--falloff", options->settings.cosine_falloff,
                  "Include the cosine falloff in the light function (AAF Sec. 7)");
    cmd->add_flag("--skip-self-occluded", options->settings.skip_self_occluded,
                  "Light samples behind the receiver's tangent plane give no occluder distance (the AAF "
                  "authors' code); by default they give an occluder at the receiver, d2 = d1");
    cmd->add_option("--resume", options->resume,
                    "Continue a progressive render from this partial output (may be the -o file)");
    cmd->add_option("--checkpoint", options->checkpoint_s,
                    "Seconds between checkpoints of a progressive render (written to -o, resumable)")
        ->capture_default_str();
    cmd->add_option("--progress", options->progress,
                    "auto (a bar with an ETA on a terminal, else lines per 10 % of a progressive render), "
                    "lines (every 10 % and every 2 s), jsonl, openjd (per round of 1024 spp) or none; "
                    "per frame for a sequence")
        ->capture_default_str();
    cmd->add_flag(
        "--skip-existing", options->skip_existing,
        "Skip frames whose output is complete (all spp, not a checkpoint) and up to date: made by this aaf "
        "with these settings from the scene files unchanged since; redo stale or partial ones");
    cmd->add_option(
        "--filter", options->filter,
        "Filter each frame with this method (aaf filter METHOD) before writing it: one process, no "
        "intermediate file; --aovs defaults to the method's inputs");
    cmd->add_option(
        "--filter-param", options->filter_params,
        "NAME=VALUE: a parameter of the --filter method, named as its option in aaf filter METHOD "
        "--help (normal-threshold=30) or as declared (normal_threshold=30); repeatable");
    cmd->add_flag(
        "--keep-beauty", options->keep_beauty,
        "With --filter: R,G,B stay the render's and the filtered image is added as aaf.R/G/B (as aaf "
        "filter --keep-beauty)");
    add_write_options(*cmd, options->write, "a complete frame (a checkpoint stays float, zip:1)");
    cmd->add_flag("--timings", options->timings,
                  "Print each frame's timings on stderr (the render's passes, maaf6's sampling and "
                  "pre-filtering, the filter); they are never written into the output");
    cmd->add_flag("--list", options->list, "List the scenes found by name and exit");
    cmd->callback([options, cmd] {
        if (options->list) {
            for (const std::string &name : trace::builtin_scene_names()) std::cout << name << "\n";
            return;
        }
        if (options->scene.empty()) throw CLI::RequiredError("scene");
        if (options->output.empty()) throw CLI::RequiredError("--output");
        require_exr_output(options->output, "aaf render");
        trace::RenderSettings &settings = options->settings;
        if (!options->light.empty()) settings.light_profile = light_profile_from_string(options->light);
        settings.plan = aaf_params_given(options->plan);
        try {
            settings.aovs = trace::parse_aov_groups(options->aovs);
        } catch (const Error &e) {
            throw UsageError(std::string("--aovs: ") + e.what());
        }
        std::optional<RenderFilter> filter;
        if (!options->filter.empty()) {
            filter = render_filter(options->filter, options->filter_params);
            const unsigned needed = trace::aov_groups_for_method(options->filter);
            // What the parameters add (--filter-param temporal=true: motion), decided before rendering.
            const unsigned with_parameters =
                needed | trace::aov_groups_writing(filter->method->roles_needed(filter->parameters));
            // A render for one of the method's delegates serves too: `--aovs maaf6 --filter aaf` runs
            // maaf6 --pairs 1 (choose_method), at the delegate's defaults.
            const MethodDelegate *served_by = nullptr;
            for (const MethodDelegate &delegate : filter->method->info().delegates) {
                const unsigned groups = trace::aov_groups_for_method(delegate.method);
                if (!served_by && (settings.aovs & groups) == groups) served_by = &delegate;
            }
            const bool own_inputs = (settings.aovs & needed) == needed;
            if (cmd->count("--aovs") == 0)
                settings.aovs = with_parameters;
            else if (own_inputs)
                check_parameter_groups(*filter, settings.aovs, options->aovs);
            else if (!own_inputs && !served_by)
                throw UsageError("--filter " + options->filter + " reads AOVs that --aovs " + options->aovs +
                                 " does not render (add " + options->filter +
                                 " to --aovs, or leave --aovs out)");
            else if (!own_inputs && !options->filter_params.empty()) {  // as `aaf filter` refuses it
                std::string name =
                    options->filter_params.front().substr(0, options->filter_params.front().find('='));
                std::replace(name.begin(), name.end(), '-', '_');  // normal-threshold is normal_threshold
                throw UsageError(delegate_parameter_refusal(*filter->method, *served_by, name));
            }
        } else if (!options->filter_params.empty()) {
            throw UsageError("--filter-param needs --filter");
        } else if (options->keep_beauty) {
            throw UsageError("--keep-beauty needs --filter");
        }
        check_settings(settings, !options->resume.empty());
        // Options that only shape the adaptive second pass do nothing without it.
        if (!settings.adaptive)
            for (const std::string &option : adaptive_option_names())
                if (cmd->count(option) > 0)
                    std::fprintf(stderr, "aaf: warning: %s has no effect without --adaptive\n",
                                 option.c_str());
        // Nor do a group's options without the group.
        if (!(settings.aovs & trace::kAovMaaf6) && cmd->count("--maaf6-effects") > 0)
            std::fprintf(stderr,
                         "aaf: warning: --maaf6-effects has no effect without the maaf6 group (--aovs "
                         "maaf6)\n");
        if (!(options->checkpoint_s > 0)) throw UsageError("--checkpoint must be positive");
        settings.checkpoint_interval_s = options->checkpoint_s;

        // An empty --frames would otherwise mean a single render.
        if (cmd->count("--frames") > 0 && options->frames.empty())
            throw UsageError("--frames: empty frame range (e.g. 1-24)");
        const bool sequence = !options->frames.empty();
        if (sequence != io::is_sequence_pattern(options->output))
            throw UsageError(sequence ? "--frames needs an output pattern such as shot.####.exr"
                                      : "an output pattern needs --frames");
        if (sequence && !options->resume.empty())
            throw UsageError("--resume continues a single render, not a sequence");

        // Frames are produced as they come: `--frames 1-2000000000` costs one job's memory.
        std::optional<io::FrameRange> frames;
        if (sequence) frames = sequence_frames(options->output, options->frames);
        check_outputs_spare_inputs(options->scene, options->output, frames);
        const FrameJobs jobs =
            frames ? FrameJobs(FrameJobs::fixed_input(options->scene), options->output, *frames)
                   : FrameJobs({{0, options->scene, options->output}});
        std::optional<AovSet> partial;
        if (!options->resume.empty()) {
            partial = io::read_aovs(options->resume);
            settings.resume = &*partial;
            settings.resume_source = options->resume;
        }
        RunOptions run;
        run.progress = progress_from_string(options->progress);
        run.skip_existing = options->skip_existing;
        const std::string scene_hash = inputs_hash(trace::scene_input_files(options->scene));
        // One pipeline for the whole sequence: a method that reads the
        // previous frame's output gets it, as in `aaf filter`.
        std::optional<io::FrameFilter> frame_filter;
        io::FilterFileOptions filter_options;
        if (filter) {
            frame_filter = io::method_filter(*filter->method, filter->parameters, filter_options.channels);
            filter_options.threads = settings.threads;
            filter_options.keep_beauty = options->keep_beauty;
        }
        // A filter that reads the previous frame's output (ratio --temporal):
        // frame f's history is frame f - 1's, back to the sequence's start,
        // the scene's first key frame (frame 1 without animation), whatever
        // frames this run renders.
        std::optional<FrameHistory> history;
        const auto job_provenance = [&](const FrameJob &job) {
            trace::RenderSettings frame_settings = settings;
            if (sequence) frame_settings.frame = job.frame;
            std::string parameters = render_parameters(frame_settings);
            if (filter) parameters += filter_parameters(*filter);
            // Only where they differ from the defaults, so that earlier outputs stay up to date.
            if (options->keep_beauty) parameters += " keep_beauty=true";
            if (options->write.half_colour) parameters += " half=true";
            if (options->write.compression != io::WriteOptions{}.compression)
                parameters += " compression=" + options->write.compression;
            // Every frame renders the same scene files: its history adds only the frames it reads.
            return Provenance{"render", parameters, scene_hash,
                              history ? history->frames_read(job.frame) : ""};
        };
        const auto frame_settings_of = [&](int frame) {
            trace::RenderSettings frame_settings = settings;
            if (sequence) frame_settings.frame = frame;
            frame_settings.stop_requested = [] { return interrupt_received != 0; };
            return frame_settings;
        };
        // Filters a complete render in memory; returns the seconds it took.
        const auto filter_render = [&](AovSet &aovs, const std::string &source, bool report_notes) {
            const Method &chosen =
                *choose_method(*filter->method, filter->parameters, aovs, filter_options.channels).method;
            const std::vector<std::string> recipes =
                missing_input_recipes(chosen, aovs, filter_options.channels);
            if (!recipes.empty()) throw InputError(missing_inputs_message(chosen, recipes));
            const auto start = std::chrono::steady_clock::now();
            io::FilterFileReport report;
            aovs = io::filter_frame(std::move(aovs), source, *frame_filter, filter_options, report);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (!report_notes) return seconds;
            for (const std::string &note : report.notes)
                std::fprintf(stderr, "aaf: note: %s\n", note.c_str());
            for (const std::string &warning : report.warnings)
                std::fprintf(stderr, "aaf: warning: %s\n", warning.c_str());
            return seconds;
        };
        if (sequence && frame_filter && frame_filter->reads_history) {
            const std::optional<double> first_key = trace::scene_first_key_frame(options->scene);
            const double start_frame = first_key ? std::floor(*first_key) : 1.0;
            FrameHistory::Source source;
            source.sequence_start = [start_frame](int frame) {
                return double(frame) <= start_frame ? frame : int(start_frame);
            };
            source.identity = [](int, bool) { return std::string(); };  // the scene hash covers it
            source.replay = [&](int frame) {
                AovSet aovs = trace::render_scene(options->scene, frame_settings_of(frame));
                if (std::get<int>(aovs.attributes.at(attr::kSppDone)) < settings.spp) throw Interrupted{};
                filter_render(aovs, options->scene, /*report_notes=*/false);
            };
            source.forget = [&frame_filter] { frame_filter->forget_history(); };
            history.emplace(std::move(source));
        }
        run.up_to_date = [&](const FrameJob &job) {
            return output_up_to_date(job.output, job_provenance(job));
        };
        RenderReporter reporter(sequence ? Progress::None : run.progress);
        std::signal(SIGINT, on_interrupt);
        std::signal(SIGTERM, on_interrupt);
        const std::size_t failed = run_frames(jobs, run, [&](const FrameJob &job) {
            if (interrupt_received) throw Interrupted{};  // the frames so far are complete
            trace::RenderSettings frame_settings = frame_settings_of(job.frame);
            frame_settings.on_progress = [&](int done, int total) { reporter.round(done, total); };
            frame_settings.on_round_progress = [&](double done, int total) {
                reporter.within_round(done, total);
            };
            const Provenance provenance = job_provenance(job);
            frame_settings.on_checkpoint = [&](const AovSet &so_far) {
                AovSet stamped = so_far;
                stamp(provenance, stamped);
                io::write_aovs(stamped, job.output);
            };
            if (history) history->prepare(job.frame);
            trace::RenderTimings timings;
            // Scene and resume errors name their file themselves.
            AovSet aovs = trace::render_scene(job.input, frame_settings, &timings);
            const int done = std::get<int>(aovs.attributes.at(attr::kSppDone));
            // Statistics of the render, taken before the filter may replace its channels.
            const ChannelMap channels;
            const double mean_spp =
                settings.adaptive
                    ? mean_spp_over_shaded(aovs.channel(channels.channel(Role::SamplesPerPixel)),
                                           aovs.channel(channels.channel(Role::ObjectId)))
                    : 0.0;
            double filter_s = 0;
            // An interrupted render is written unfiltered, so that --resume can continue it.
            if (frame_filter && done >= frame_settings.spp)
                filter_s = filter_render(aovs, job.input, /*report_notes=*/true);
            stamp(provenance, aovs);
            if (done < frame_settings.spp) {
                io::write_aovs(aovs, job.output);  // as a checkpoint: exact, for --resume
                std::fprintf(
                    stderr, "aaf: interrupted after %d of %d spp; %s holds them: continue with --resume %s\n",
                    done, frame_settings.spp, job.output.c_str(), job.output.c_str());
                throw Interrupted{};
            }
            io::write_aovs(aovs, job.output, options->write);
            if (history) history->filtered(job.frame);
            if (settings.adaptive) {
                std::printf(
                    "adaptive sampling: average %.2f spp over shaded pixels; first pass %.3f s, "
                    "plan %.3f s, second pass %.3f s",
                    mean_spp, timings.first_pass_s, timings.plan_s, timings.second_pass_s);
                if (frame_filter) std::printf(", filter %.3f s", filter_s);
                std::printf("\n");
            }
            if (options->timings) {
                std::fprintf(stderr, "aaf: timings: %s: light passes %.3f s", job.output.c_str(),
                             timings.first_pass_s + timings.plan_s + timings.second_pass_s);
                if (settings.aovs & trace::kAovMaaf6)
                    std::fprintf(stderr, ", maaf6 sampling %.3f s, pre-filtering %.3f s",
                                 timings.maaf6_sampling_s, timings.maaf6_prefilter_s);
                if (frame_filter) std::fprintf(stderr, ", filter %.3f s", filter_s);
                std::fprintf(stderr, "\n");
            }
        });
        if (failed > 0)
            throw Error(std::to_string(failed) + " of " + std::to_string(jobs.size()) + " frames failed");
    });
}

}  // namespace aaf::cli
