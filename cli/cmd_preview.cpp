#include <memory>
#include <string>
#include <vector>

#include "aaf/core/error.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/preview.h"
#include "commands.h"
#include "input_guard.h"

namespace aaf::cli {

void add_preview_command(CLI::App &app) {
    struct Options {
        std::string input, output;
        std::vector<std::string> channels{"R", "G", "B"};
        float exposure = 0;
        std::vector<float> range;
        bool false_colour = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand("preview", "Write an sRGB PNG preview of an EXR's channels");
    cmd->add_option("input", options->input, "Input image")->required();
    cmd->add_option("-o,--output", options->output, "Output PNG")->required();
    cmd->add_option("--channels", options->channels, "One channel (grey) or three")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--exposure", options->exposure, "Exposure, stops")->capture_default_str();
    cmd->add_flag("--false-colour", options->false_colour,
                  "One channel in false colour, 0 in black (AAF Fig. 7 style for aaf.beta, plan.spp)");
    cmd->add_option("--range", options->range,
                    "Value range LOW,HIGH of the false colours (default: data range)")
        ->delimiter(',')
        ->expected(2);
    cmd->callback([options] {
        check_not_same_file(options->input, options->output);
        const AovSet aovs = io::read_aovs(options->input);
        if (options->false_colour) {
            if (options->channels.size() != 1)
                throw Error(options->output + ": --false-colour takes one channel");
            const float low = options->range.empty() ? 0.0f : options->range[0];
            const float high = options->range.empty() ? 0.0f : options->range[1];
            io::write_false_colour_png(aovs, options->channels[0], options->output, low, high);
            return;
        }
        io::write_preview_png(aovs, options->channels, options->output, options->exposure);
    });
}

}  // namespace aaf::cli
