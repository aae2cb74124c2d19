#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/channel_lookup.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/preview.h"
#include "channel_options.h"
#include "commands.h"
#include "suggestion.h"

namespace aaf::cli {

namespace {

/// The channels of layer `layer` to show: LAYER.R/G/B, else LAYER.X/Y/Z,
/// else its only channel; throws aaf::InputError listing what it has.
std::vector<std::string> layer_channels(const AovSet &aovs, const std::string &layer) {
    std::vector<std::string> members;
    for (const std::string &name : aovs.channel_names())
        if (name.size() > layer.size() + 1 && name.compare(0, layer.size() + 1, layer + ".") == 0 &&
            name.find('.', layer.size() + 1) == std::string::npos)
            members.push_back(name);
    for (const std::vector<std::string> &suffixes :
         {std::vector<std::string>{"R", "G", "B"}, std::vector<std::string>{"X", "Y", "Z"}}) {
        std::vector<std::string> names;
        for (const std::string &suffix : suffixes)
            if (aovs.has_channel(layer + "." + suffix)) names.push_back(layer + "." + suffix);
        if (names.size() == 3) return names;
    }
    if (members.size() == 1) return members;
    std::string listed;
    for (const std::string &name : members) listed += (listed.empty() ? "" : ", ") + name;
    throw InputError("layer '" + layer + "' has no R,G,B, X,Y,Z or single channel to show" +
                     (listed.empty() ? " (no such layer)" : " (it has " + listed + ")"));
}

/// Refuses channels `input` does not have, naming the input (the output is
/// not at fault), listing what it has and the one most like the name.
void check_channels_present(const AovSet &aovs, const std::vector<std::string> &channels,
                            const std::string &input) {
    for (const std::string &name : channels)
        if (!aovs.has_channel(name)) {
            std::string listed;
            for (const std::string &present : aovs.channel_names())
                listed += (listed.empty() ? "" : ", ") + present;
            throw InputError(input + ": no channel '" + name + "' to preview (it has " + listed + ")" +
                             did_you_mean(name, aovs.channel_names()));
        }
}

}  // namespace

void add_preview_command(CLI::App &app) {
    struct Options {
        std::string input, output, layer;
        std::vector<std::string> channels{"R", "G", "B"};
        std::vector<float> range;
        bool false_colour = false;
        io::PreviewOptions preview;
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand(
        "preview", "Write a PNG preview: colour through an OpenColorIO display/view, data as it is");
    cmd->add_option("input", options->input, "Input image")->required();
    cmd->add_option("-o,--output", options->output, "Output PNG, or JPEG for .jpg/.jpeg")->required();
    cmd->add_option("--channels", options->channels, "One channel (grey) or three")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--layer", options->layer, "Show a layer: LAYER.R/G/B, LAYER.X/Y/Z or its one channel");
    cmd->add_option("--ocio-config", options->preview.ocio_config,
                    "OpenColorIO config (default: $OCIO, else the config embedded in aaf)");
    cmd->add_option("--display", options->preview.display, "OCIO display (default: the config's default)");
    cmd->add_option("--view", options->preview.view, "OCIO view (default: the display's default)");
    cmd->add_option("--colorspace", options->preview.input_space,
                    "Colour space of the input (default: the config's scene_linear role)");
    cmd->add_option("--exposure", options->preview.exposure_stops, "Exposure, stops")
        ->check(finite_number(-HUGE_VAL, HUGE_VAL, /*low_allowed=*/true))
        ->capture_default_str();
    cmd->add_flag("--false-colour", options->false_colour,
                  "One channel in false colour, 0 in black (AAF Fig. 7 style for aaf_beta.X, plan.spp)");
    cmd->add_option("--range", options->range,
                    "Value range LOW,HIGH of the false colours (default: data range)")
        ->delimiter(',')
        ->expected(2)
        ->check(finite_number(-HUGE_VAL, HUGE_VAL, /*low_allowed=*/true));
    cmd->callback([options, cmd] {
        require_display_image_name(options->output, "--output");
        // The colour pipeline and the false-colour ramp take different options.
        const std::vector<const char *> unused =
            options->false_colour ? std::vector<const char *>{"--ocio-config", "--display", "--view",
                                                              "--colorspace", "--exposure"}
                                  : std::vector<const char *>{"--range"};
        for (const char *option : unused)
            if (cmd->count(option) > 0)
                std::fprintf(stderr, "aaf: warning: %s has no effect %s --false-colour\n", option,
                             options->false_colour ? "with" : "without");
        if (options->layer.empty() && options->channels.size() != 1 && options->channels.size() != 3)
            throw UsageError("--channels: a preview shows one channel (grey) or three");
        io::check_not_same_file(options->input, options->output);
        if (!options->false_colour) try {
                io::check_display_view(options->preview);  // the config's own problems are input errors
            } catch (const InputError &) {
                throw;
            } catch (const Error &e) {
                throw UsageError(e.what());  // an unknown --display, --view or --colorspace
            }
        io::ImageLayout layout;
        const AovSet aovs = io::read_aovs(options->input, &layout);
        // R, G, B (or shadow.V...) as the renderer names them, as `aaf compare` finds them.
        std::vector<std::string> channels;
        for (const std::string &name : options->channels) channels.push_back(io::resolve_channel(name, aovs));
        if (!options->layer.empty())
            channels = with_context(options->input, [&] { return layer_channels(aovs, options->layer); });
        check_channels_present(aovs, channels, options->input);
        if (options->false_colour) {
            if (channels.size() != 1)
                throw UsageError(options->output + ": --false-colour takes one channel");
            const float low = options->range.empty() ? 0.0f : options->range[0];
            const float high = options->range.empty() ? 0.0f : options->range[1];
            io::write_false_colour_png(aovs, channels[0], options->output, low, high);
            return;
        }
        // The picture is the display window; the pixels sit at the data window.
        io::PreviewOptions preview = options->preview;
        preview.data_window = layout.data_window();
        preview.display_window = layout.display_window();
        io::write_preview_png(aovs, channels, options->output, preview);
    });
}

}  // namespace aaf::cli
