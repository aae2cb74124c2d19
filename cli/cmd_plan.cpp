#include <memory>
#include <string>
#include <vector>

#include "aaf/core/methods/aaf/sampling_plan.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
#include "channel_options.h"
#include "commands.h"
#include "parameter_options.h"

namespace aaf::cli {

void add_plan_command(CLI::App &app) {
    struct Options {
        std::string input, output;
        GivenParameters aaf;  ///< AAF's parameters given, as `aaf filter aaf` takes them
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
    // AAF's own parameters, declared once (aaf_parameter_declarations()): the plan must use the filter's.
    add_aaf_option(*cmd, "mu", options->aaf, "mu of AAF Eq. 21 (use the filter's)");
    add_aaf_option(*cmd, "alpha", options->aaf);
    add_aaf_option(*cmd, "light_bandlimit", options->aaf,
                   "Light band-limit rule (use the filter's --light-bandlimit)");
    add_aaf_option(*cmd, "light_axes", options->aaf, "Light axes rule (use the filter's --light-axes)");
    add_aaf_option(*cmd, "pixel_footprint", options->aaf,
                   "Pixel footprint (use the filter's --pixel-footprint; projected needs the normal)");
    cmd->add_option("--first-pass", options->plan.first_pass_spp, "Samples the first pass took per pixel")
        ->check(finite_number(1, HUGE_VAL, /*low_allowed=*/true))
        ->capture_default_str();
    cmd->add_option("--max-spp", options->plan.max_spp, "Cap on the total per pixel")
        ->check(finite_number(1, HUGE_VAL, /*low_allowed=*/true))
        ->capture_default_str();
    add_aaf_option(*cmd, "fill_radius", options->aaf);
    add_map_and_threads_options(*cmd, options->maps, options->threads);
    cmd->callback([options] {
        if (options->plan.first_pass_spp > options->plan.max_spp)
            throw UsageError("--first-pass " + std::to_string(options->plan.first_pass_spp) +
                             " is above --max-spp " + std::to_string(options->plan.max_spp));
        const AafParams aaf = aaf_params_given(options->aaf);
        const ChannelMap channels = channel_map_from(options->maps);
        require_exr_output(options->output, "aaf plan");
        io::check_not_same_file(options->input, options->output);
        const AovSet input = io::read_aovs(options->input);
        AovSet plan;
        run_with_threads(options->threads, [&] {
            with_context(options->input,
                         [&] { plan = plan_samples_aovs(input, channels, aaf, options->plan); });
        });
        io::write_aovs(plan, options->output);
    });
}

}  // namespace aaf::cli
