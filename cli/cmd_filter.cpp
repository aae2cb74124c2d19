#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/filter_file.h"
#include "channel_options.h"
#include "commands.h"
#include "frame_runner.h"

namespace aaf::cli {

namespace {

/// The channels AAF reads, so they are borrowed from other parts and bad
/// values there are replaced before filtering.
std::vector<std::string> filter_inputs(const ChannelMap &channels) {
    std::vector<std::string> names;
    std::vector<Role> roles = method_table().front().required;
    roles.insert(roles.end(), {Role::Beauty, Role::SamplesPerPixel, Role::OtherLights});
    for (Role role : roles)
        for (const std::string &name : channels.channels(role)) names.push_back(name);
    return names;
}

/// AAF as the file pipeline runs it.
io::FrameFilter aaf_frame_filter(const ChannelMap &channels, const AafParams &params) {
    io::FrameFilter filter;
    filter.input_channels = [channels](const AovSet &input) {
        return filter_inputs(channels.resolved(input));
    };
    filter.run = [channels, params](const AovSet &input) { return aaf_filter_aovs(input, channels, params); };
    return filter;
}

/// The command line of `aaf filter aaf`.
struct Options {
    std::string input, output;
    AafParams params;
    std::vector<std::string> maps;
    int threads = 0;
    std::string mode = "separable";
    std::string frames, progress = "auto";
    bool skip_existing = false, skip_bad_frames = false;
    bool replace_beauty = true;
    io::WriteOptions write;
};

/// Filters each frame of the command line, printing each frame's warnings.
void run_filter(const Options &o) {
    const ChannelMap channels = channel_map_from(o.maps);
    AafParams params = o.params;
    params.mode = o.mode == "2d" ? AafFilterMode::Exact2D : AafFilterMode::Separable;
    RunOptions run;
    run.progress = progress_from_string(o.progress);
    run.skip_existing = o.skip_existing;
    run.skip_bad_frames = o.skip_bad_frames;
    io::FilterFileOptions file;
    file.channels = channels;
    file.keep_beauty = !o.replace_beauty;
    file.threads = o.threads;
    file.write = o.write;
    const io::FrameFilter filter = aaf_frame_filter(channels, params);
    const std::vector<FrameJob> jobs = frame_jobs(o.input, o.output, o.frames);
    // Frames stream one at a time (bounded memory); the filter itself runs on all threads.
    const int failed = run_frames(jobs, run, [&](const FrameJob &job) {
        const io::FilterFileReport report = io::filter_file(job.input, job.output, filter, file);
        for (const std::string &warning : report.warnings)
            std::fprintf(stderr, "aaf: warning: %s\n", warning.c_str());
    });
    if (failed > 0)
        throw Error(std::to_string(failed) + " of " + std::to_string(jobs.size()) + " frames failed");
}

void add_aaf_method(CLI::App &filter) {
    auto options = std::make_shared<Options>();
    CLI::App *cmd =
        filter.add_subcommand("aaf", "Axis-Aligned Filtering of soft shadows (Mehta et al. 2012)");
    cmd->add_option("input", options->input, "Input EXR with the AAF AOVs, or a sequence (shot.####.exr)")
        ->required();
    cmd->add_option("-o,--output", options->output, "Output EXR, or a sequence pattern for a sequence")
        ->required();
    cmd->add_option("--frames", options->frames, "Frames of a sequence: 1-100, 1-100x2, 1-100:2, 1,5,7-9");
    cmd->add_option("--progress", options->progress, "auto, lines, jsonl, openjd or none")
        ->capture_default_str();
    cmd->add_flag("--skip-existing", options->skip_existing,
                  "Skip frames whose output exists and reads back");
    cmd->add_flag("--skip-bad-frames", options->skip_bad_frames,
                  "Report a failed frame and continue (the exit code is still non-zero)");
    cmd->add_flag("--replace-beauty,!--keep-beauty", options->replace_beauty,
                  "R,G,B become the filtered image, the input's kept as noisy.R/G/B (default); "
                  "--keep-beauty leaves R,G,B as they were and adds the filtered image as aaf.R/G/B");
    cmd->add_flag(
        "--half", options->write.half_colour,
        "Store colour layers (beauty, unshadowed, albedo, unclaimed LAYER.R/G/B/A) as half; data layers "
        "(P, N, ... whatever their names) stay float");
    cmd->add_option("--compression", options->write.compression,
                    "EXR compression: zip, zips, piz, rle, none, or the lossy dwaa/dwab (colour layers only: "
                    "the data layers then go to a ZIP part named 'data')")
        ->check(CLI::IsMember({"zip", "zips", "piz", "rle", "none", "dwaa", "dwab"}))
        ->capture_default_str();
    AafParams &p = options->params;
    cmd->add_option("--mu", p.mu, "Filter scale for consistency, beta ~ 1/mu (Sec. 5.2)")
        ->capture_default_str();
    cmd->add_flag("--mu-from-spp", p.mu_from_spp,
                  "Per pixel, raise mu until Eq. 21's rate equals the samples taken (consistency, Sec. 5.2)");
    cmd->add_option("--k", p.k, "Gaussian spread factor of Eq. 13")->capture_default_str();
    cmd->add_option("--alpha", p.alpha, "Occluder bandlimit over pixel bandlimit, (0,1] (Eq. 5)")
        ->capture_default_str();
    cmd->add_option("--normal-threshold", p.normal_threshold_deg,
                    "Reject taps whose normal turns more, degrees")
        ->capture_default_str();
    cmd->add_option("--fill-radius", p.fill_radius_px, "Radius to borrow occluder distances, pixels")
        ->capture_default_str();
    cmd->add_option("--max-radius", p.max_radius_px, "Largest filter radius, pixels")->capture_default_str();
    cmd->add_option(
           "--filter", options->mode,
           "separable: two 1D passes (Sec. 6); 2d: exact 2D gather of Eq. 10, to measure the approximation")
        ->check(CLI::IsMember({"separable", "2d"}))
        ->capture_default_str();
    add_map_and_threads_options(*cmd, options->maps, options->threads);
    cmd->callback([options] { run_filter(*options); });
}

}  // namespace

void add_filter_command(CLI::App &app) {
    CLI::App *filter = app.add_subcommand("filter", "Filter noisy AOVs with one of the methods");
    filter->require_subcommand(1);
    add_aaf_method(*filter);
}

}  // namespace aaf::cli
