#include <algorithm>
#include <cstdio>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/kernels/sample_statistics.h"
#include "aaf/io/exr_io.h"
#include "commands.h"
#include "light_option.h"
#include "missing_input_report.h"

namespace aaf::cli {

namespace {

std::string format_attribute(const AttributeValue &value) {
    char buffer[128];
    if (const int *i = std::get_if<int>(&value)) return std::to_string(*i);
    if (const float *f = std::get_if<float>(&value)) {
        std::snprintf(buffer, sizeof buffer, "%g", *f);
        return buffer;
    }
    if (const std::string *s = std::get_if<std::string>(&value)) return "\"" + *s + "\"";
    const Vec3 &v = std::get<Vec3>(value);
    std::snprintf(buffer, sizeof buffer, "(%g, %g, %g)", v.x, v.y, v.z);
    return buffer;
}

/// The channels' lines: name, storage (an EXR's half or float; another format's
/// is its own, not named) and with --stats each one's min, max and mean.
void print_channels(const AovSet &aovs, bool exr, bool stats) {
    std::printf("channels (the first part's, then those read from other parts):\n");
    for (std::size_t c = 0; c < aovs.channel_names().size(); ++c) {
        const char *storage = !exr ? "" : aovs.precision(c) == Precision::Half ? "half" : "float";
        if (!stats) {
            std::printf(exr ? "  %-20s %s\n" : "  %s%s\n", aovs.channel_names()[c].c_str(), storage);
            continue;
        }
        const AovSet::Plane &plane = aovs.plane(c);
        auto [lo, hi] = std::minmax_element(plane.begin(), plane.end());
        const double mean = std::accumulate(plane.begin(), plane.end(), 0.0) / double(plane.size());
        std::printf("  %-20s %-5s min %-12g max %-12g mean %g\n", aovs.channel_names()[c].c_str(), storage,
                    *lo, *hi, mean);
    }
}

}  // namespace

void add_info_command(CLI::App &app) {
    struct Options {
        std::string input, light;
        bool stats = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand("info", "List channels, attributes and which methods a file can feed");
    cmd->add_option("input", options->input, "Image to describe")->required();
    cmd->add_option("--light", options->light,
                    "JSON key light (as aaf filter --light): the methods' readiness with it in place of the "
                    "file's aaf:light:* header");
    cmd->add_flag("--stats", options->stats,
                  "Read every pixel: each channel's min, max and mean, and the mean spp (without it only the "
                  "header is read)");
    cmd->callback([options] {
        io::ImageLayout layout;
        const auto light = light_option(options->light);
        // The header alone unless the pixels are asked for: instant on a frame of any size.
        AovSet aovs = options->stats ? io::read_aovs(options->input, &layout)
                                     : io::read_aov_header(options->input, layout);
        const io::PixelWindow size = layout.data_window();
        std::printf("%s: %d x %d, %zu channels\n", options->input.c_str(), size.width, size.height,
                    aovs.channel_names().size());
        // Other parts: listed, and those of the same size read as `aaf filter` reads them.
        std::vector<std::string> borrowable, borrowed_half;
        for (const io::PartSummary &part : io::other_parts(options->input, layout)) {
            std::string names;
            for (const std::string &name : part.channels) names += " " + name;
            std::printf("part %d '%s': %d x %d,%s\n", part.index, part.name.c_str(), part.width, part.height,
                        names.c_str());
            if (part.width != size.width || part.height != size.height) continue;
            for (std::size_t c = 0; c < part.channels.size(); ++c) {
                if (aovs.has_channel(part.channels[c])) continue;
                borrowable.push_back(part.channels[c]);
                if (part.half[c]) borrowed_half.push_back(part.channels[c]);
            }
        }
        if (options->stats) {
            io::add_channels_from_other_parts(options->input, layout, borrowable, aovs);
        } else {
            for (const std::string &name : borrowable) aovs.add_channel(name);
        }
        for (const std::string &name : borrowed_half)
            if (aovs.has_channel(name)) aovs.set_precision(name, Precision::Half);
        print_channels(aovs, layout.format_name() == "openexr", options->stats);
        const ChannelMap channels = ChannelMap{}.resolved(aovs);  // other renderers' names too
        const std::string &spp_name = channels.channel(Role::SamplesPerPixel);
        const std::string &id_name = channels.channel(Role::ObjectId);
        if (options->stats && aovs.has_channel(spp_name) && aovs.has_channel(id_name))
            std::printf("mean spp over shaded pixels: %g\n",
                        mean_spp_over_shaded(aovs.channel(spp_name), aovs.channel(id_name)));
        if (apply_light_option(light, aovs))
            std::printf("the light of %s replaces the file's aaf:light:* header\n", options->light.c_str());
        std::printf("attributes:\n");
        for (const auto &[name, value] : aovs.attributes)
            std::printf("  %-24s %s\n", name.c_str(), format_attribute(value).c_str());
        const auto beauty = aovs.attributes.find(attr::kBeautyEffects);
        if (beauty != aovs.attributes.end())
            std::printf("R,G,B holds %s (aaf:beauty_effects), not the direct light of every light\n",
                        format_attribute(beauty->second).c_str());
        const auto holds = aovs.attributes.find(attr::kBeauty);
        if (holds != aovs.attributes.end())
            std::printf("R,G,B is %s (aaf:beauty): what the filters replace their estimate in\n",
                        format_attribute(holds->second).c_str());
        std::printf("methods (what each lacks, with how to produce it):\n");
        for (const Method *method : methods()) {
            // A render made for one of its delegates is ready too, as that delegate (choose_method).
            // The plan's note also says when the method would keep R,G,B as rendered.
            const FilterPlan plan = prepare_filter(*method, method->default_parameters(), aovs, channels);
            const std::vector<std::string> recipes = missing_input_recipes(*plan.method, aovs, channels);
            const std::string status = !recipes.empty()    ? "missing " + std::to_string(recipes.size())
                                       : plan.note.empty() ? std::string("ready")
                                                           : "ready: " + plan.note;
            std::printf("  %-8s %s\n", method->info().name.c_str(), status.c_str());
            for (const std::string &recipe : recipes) std::printf("             - %s\n", recipe.c_str());
        }
    });
}

}  // namespace aaf::cli
