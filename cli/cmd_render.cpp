#include <cstdio>
#include <iostream>

#include <memory>
#include "aaf/core/aov_contract.h"
#include "aaf/core/sample_statistics.h"

#include "aaf/io/exr_io.h"
#include "aaf/trace/render.h"
#include "commands.h"

namespace aaf::cli {

void add_render_command(CLI::App &app) {
    struct Options {
        std::string scene;
        std::string output;
        trace::RenderSettings settings;
        bool list = false;
        std::string light;
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand("render", "Render a built-in scene to a multi-layer EXR of AOVs");
    cmd->add_option("scene", options->scene, "Built-in scene name (see --list)");
    cmd->add_option("-o,--output", options->output, "Output EXR path");
    cmd->add_option("--width", options->settings.width, "Image width, pixels")->capture_default_str();
    cmd->add_option("--height", options->settings.height, "Image height, pixels")->capture_default_str();
    cmd->add_option("--spp", options->settings.spp, "Light samples per pixel, stratified over the light")
        ->capture_default_str();
    cmd->add_option("--seed", options->settings.seed, "Random seed")->capture_default_str();
    cmd->add_option("--threads", options->settings.threads, "Worker threads, 0 = all (output is identical)")
        ->capture_default_str();
    cmd->add_flag("--adaptive", options->settings.adaptive,
                  "Two-pass adaptive sampling (AAF Sec. 6): --spp first, then Eq. 21 per pixel");
    cmd->add_option("--mu", options->settings.adaptive_mu, "mu of the adaptive sampling rate (Eq. 21)")
        ->capture_default_str();
    cmd->add_option("--max-spp", options->settings.max_spp, "Cap on the adaptive samples per pixel")
        ->capture_default_str();
    cmd->add_option("--light", options->light, "Override the light's profile: gaussian or uniform")
        ->check(CLI::IsMember({"gaussian", "uniform"}));
    cmd->add_flag("--falloff", options->settings.cosine_falloff,
                  "Include the cosine falloff in the light function (AAF Sec. 7)");
    cmd->add_flag("--list", options->list, "List the built-in scenes and exit");
    cmd->callback([options] {
        if (options->list) {
            for (const std::string &name : trace::builtin_scene_names()) std::cout << name << "\n";
            return;
        }
        if (options->scene.empty()) throw CLI::RequiredError("scene");
        if (options->output.empty()) throw CLI::RequiredError("--output");
        if (!options->light.empty())
            options->settings.light_profile = light_profile_from_string(options->light);
        trace::RenderTimings timings;
        AovSet aovs = trace::render_builtin(options->scene, options->settings, &timings);
        io::write_aovs(aovs, options->output);
        if (options->settings.adaptive) {
            const ChannelMap channels;
            std::printf(
                "adaptive sampling: average %.2f spp over shaded pixels; first pass %.3f s, "
                "plan %.3f s, second pass %.3f s\n",
                mean_spp_over_shaded(aovs.channel(channels.channel(Role::SamplesPerPixel)),
                                     aovs.channel(channels.channel(Role::ObjectId))),
                timings.first_pass_s, timings.plan_s, timings.second_pass_s);
        }
    });
}

}  // namespace aaf::cli
