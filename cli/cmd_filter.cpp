#include <memory>
#include <string>
#include <vector>

#include <algorithm>
#include <cstdio>

#include "aaf/core/aaf_filter.h"
#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/core/non_finite.h"
#include "aaf/core/parallel.h"
#include "aaf/io/exr_io.h"
#include "channel_options.h"
#include "commands.h"
#include "frame_runner.h"

namespace aaf::cli {

namespace {

/// The channels AAF reads, so bad values there are replaced before filtering.
std::vector<std::string> filter_inputs(const ChannelMap &channels) {
    std::vector<std::string> names;
    std::vector<Role> roles = method_table().front().required;
    roles.insert(roles.end(), {Role::Beauty, Role::SamplesPerPixel, Role::OtherLights});
    for (Role role : roles)
        for (const std::string &name : channels.channels(role)) names.push_back(name);
    return names;
}

/// One warning line per file that had NaN or infinite inputs.
void report_non_finite(const std::string &path, const NonFiniteCounts &counts) {
    if (counts.empty()) return;
    std::size_t total = 0;
    std::string detail;
    for (const auto &[name, count] : counts) {
        total += count;
        detail += (detail.empty() ? "" : ", ") + name + " " + std::to_string(count);
    }
    std::fprintf(stderr, "aaf: warning: %s: replaced %zu NaN/Inf input values by 0 (%s)\n", path.c_str(),
                 total, detail.c_str());
}

/// A set with `aovs`' attributes and, in order, the channel `from` of each
/// (from, to) pair under the name `to` (values and storage precision copied).
AovSet with_channels(const AovSet &aovs, const std::vector<std::pair<std::string, std::string>> &from_to) {
    AovSet out(aovs.width(), aovs.height());
    out.attributes = aovs.attributes;
    const std::vector<std::string> &names = aovs.channel_names();
    for (const auto &[from, to] : from_to) {
        const std::size_t index = std::size_t(std::find(names.begin(), names.end(), from) - names.begin());
        PlaneView plane = out.add_channel(to);
        std::copy(aovs.plane(index).begin(), aovs.plane(index).end(), plane.data);
        out.set_precision(to, aovs.precision(index));
    }
    return out;
}

bool contains(const std::vector<std::string> &names, const std::string &name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

/// AAF models soft shadows only: say so when the input's beauty was defocused.
void warn_if_defocused(const std::string &path, const AovSet &aovs) {
    auto it = aovs.attributes.find(attr::kApertureRadius);
    const float *aperture = it == aovs.attributes.end() ? nullptr : std::get_if<float>(&it->second);
    if (aperture && *aperture > 0)
        std::fprintf(stderr,
                     "aaf: warning: %s: rendered through a thin lens; AAF filters the in-focus shadow, "
                     "its output R,G,B has no defocus\n",
                     path.c_str());
}

/// The filter's output with the input beauty back in R,G,B (or the renderer's
/// beauty layer) and the filtered image as aaf.R/G/B (--keep-beauty).
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

void add_aaf_method(CLI::App &filter) {
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
            // The input's header (every attribute, the windows) and its other
            // parts go through to the output unchanged.
            io::ImageLayout layout;
            AovSet input = io::read_aovs(job.input, &layout);
            // AOVs the first part lacks may sit in other parts (one AOV per part);
            // they are read for the filter and stay in their parts in the output.
            const std::vector<std::string> borrowed = io::add_channels_from_other_parts(
                job.input, layout, filter_inputs(channels.resolved(input)), input);
            // Resolved again: the borrowed channels may complete a synonym.
            warn_if_defocused(job.input, input);
            report_non_finite(job.input, replace_non_finite(input, filter_inputs(channels.resolved(input))));
            AovSet output;
            run_with_threads(options->threads, [&] {
                with_context(job.input, [&] { output = aaf_filter_aovs(input, channels, options->params); });
            });
            if (!options->replace_beauty) output = keep_beauty(output, channels.resolved(input));
            if (!borrowed.empty()) output = without_channels(output, borrowed);
            io::WriteOptions write = options->write;
            write.layout = &layout;
            io::write_aovs(output, job.output, write);
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
