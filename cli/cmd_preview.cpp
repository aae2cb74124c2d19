#include <memory>
#include <string>
#include <vector>

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
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand("preview", "Write an sRGB PNG preview of an EXR's channels");
    cmd->add_option("input", options->input, "Input image")->required();
    cmd->add_option("-o,--output", options->output, "Output PNG")->required();
    cmd->add_option("--channels", options->channels, "One channel (grey) or three")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--exposure", options->exposure, "Exposure, stops")->capture_default_str();
    cmd->callback([options] {
        check_not_same_file(options->input, options->output);
        io::write_preview_png(io::read_aovs(options->input), options->channels, options->output,
                              options->exposure);
    });
}

}  // namespace aaf::cli
