#include <memory>
#include <string>
#include <vector>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/error.h"
#include "aaf/io/exr_io.h"
#include "channel_options.h"
#include "commands.h"
#include "frame_runner.h"
#include "input_guard.h"
#include "threads.h"

namespace aaf::cli {

namespace {

void add_aaf_method(CLI::App &filter) {
    struct Options {
        std::string input, output;
        AafParams params;
        std::vector<std::string> maps;
        int threads = 0;
        std::string mode = "separable";
        std::string frames, progress = "auto";
        bool skip_existing = false, skip_bad_frames = false;
    };
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
    cmd->callback([options] {
        const ChannelMap channels = channel_map_from(options->maps);
        options->params.mode = options->mode == "2d" ? AafFilterMode::Exact2D : AafFilterMode::Separable;
        RunOptions run;
        run.progress = progress_from_string(options->progress);
        run.skip_existing = options->skip_existing;
        run.skip_bad_frames = options->skip_bad_frames;
        const std::vector<FrameJob> jobs = frame_jobs(options->input, options->output, options->frames);
        // Frames stream one at a time (bounded memory); the filter itself runs on all threads.
        const int failed = run_frames(jobs, run, [&](const FrameJob &job) {
            const AovSet input = io::read_aovs(job.input);
            AovSet output;
            run_with_threads(options->threads, [&] {
                with_context(job.input, [&] { output = aaf_filter_aovs(input, channels, options->params); });
            });
            io::write_aovs(output, job.output);
        });
        if (failed > 0)
            throw Error(std::to_string(failed) + " of " + std::to_string(jobs.size()) + " frames failed");
    });
}

}  // namespace

void add_filter_command(CLI::App &app) {
    CLI::App *filter = app.add_subcommand("filter", "Filter noisy AOVs with one of the methods");
    filter->require_subcommand(1);
    add_aaf_method(*filter);
}

}  // namespace aaf::cli
