#include <memory>
#include <string>
#include <vector>

#include "aaf/core/error.h"
#include "aaf/core/sampling_plan.h"
#include "aaf/core/thread_count.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
#include "channel_options.h"
#include "commands.h"

namespace aaf::cli {

void add_plan_command(CLI::App &app) {
    struct Options {
        std::string input, output;
        AafParams aaf;
        std::string light_bandlimit = to_string(AafParams{}.light_bandlimit);
        std::string light_axes = to_string(AafParams{}.light_axes);
        std::string pixel_footprint = AafParams{}.projected_pixel ? "projected" : "receiver";
        SamplingPlanParams plan;
        std::vector<std::string> maps;
        int threads = 0;
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand(
        "plan", "Per-pixel sample counts (AAF Eq. 21) for a first-pass EXR from any renderer");
    cmd->add_option("input", options->input, "First-pass EXR with d1, d2min, d2max, object id, pixel size")
        ->required();
    cmd->add_option("-o,--output", options->output, "Output EXR with the plan.spp channel")->required();
    cmd->add_option("--mu", options->aaf.mu, "mu of AAF Eq. 21 (use the filter's)")
        ->check(finite_number(0))
        ->capture_default_str();
    cmd->add_option("--alpha", options->aaf.alpha,
                    "Occluder bandlimit over pixel bandlimit, (0,1] (AAF Eq. 5)")
        ->check(finite_number(0, 1))
        ->capture_default_str();
    cmd->add_option("--light-bandlimit", options->light_bandlimit,
                    "Light band-limit rule (use the filter's --light-bandlimit)")
        ->check(CLI::IsMember({"spectrum", "equivalent_width", "sigma"}))
        ->capture_default_str();
    cmd->add_option("--light-axes", options->light_axes, "Light axes rule (use the filter's --light-axes)")
        ->check(CLI::IsMember({"per_axis", "shortest"}))
        ->capture_default_str();
    cmd->add_option("--pixel-footprint", options->pixel_footprint,
                    "Pixel footprint (use the filter's --pixel-footprint; projected needs the normal)")
        ->check(CLI::IsMember({"projected", "receiver"}))
        ->capture_default_str();
    cmd->add_option("--first-pass", options->plan.first_pass_spp, "Samples the first pass took per pixel")
        ->check(finite_number(1, HUGE_VAL, /*low_allowed=*/true))
        ->capture_default_str();
    cmd->add_option("--max-spp", options->plan.max_spp, "Cap on the total per pixel")
        ->check(finite_number(1, HUGE_VAL, /*low_allowed=*/true))
        ->capture_default_str();
    cmd->add_option("--fill-radius", options->aaf.fill_radius_px,
                    "Radius to borrow occluder distances, pixels")
        ->check(finite_number(0, HUGE_VAL, /*low_allowed=*/true))
        ->capture_default_str();
    add_map_and_threads_options(*cmd, options->maps, options->threads);
    cmd->callback([options] {
        if (options->plan.first_pass_spp > options->plan.max_spp)
            throw UsageError("--first-pass " + std::to_string(options->plan.first_pass_spp) +
                             " is above --max-spp " + std::to_string(options->plan.max_spp));
        options->aaf.light_bandlimit = light_bandlimit_from_string(options->light_bandlimit);
        options->aaf.light_axes = light_axes_from_string(options->light_axes);
        options->aaf.projected_pixel = options->pixel_footprint == "projected";
        const ChannelMap channels = channel_map_from(options->maps);
        require_exr_output(options->output, "aaf plan");
        io::check_not_same_file(options->input, options->output);
        const AovSet input = io::read_aovs(options->input);
        AovSet plan;
        run_with_threads(options->threads, [&] {
            with_context(options->input,
                         [&] { plan = plan_samples_aovs(input, channels, options->aaf, options->plan); });
        });
        io::write_aovs(plan, options->output);
    });
}

}  // namespace aaf::cli
