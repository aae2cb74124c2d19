// Where `aaf filter maaf6` uses MAAF's partition on a maaf6 render, and why
// it falls back to the central (axis-aligned) filter elsewhere: per layer,
// the filtered pixels by the reasons of aaf::maaf6_filter_components()
// ((a) the central component reaches beyond the window, (b) the x band clips
// the wedge, (c) the focal-plane box), counted by aaf::maaf6_partition_census()
// with the filter's own parameters; "cut": of the partition's pixels, those
// whose window the guides or the border cut (the central filter there too);
// "widened": the pixels whose bands --band-spp widens (the central filter).
// Prints a table.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <variant>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/methods/maaf6/maaf6_filter.h"
#include "aaf/core/methods/maaf6/maaf6_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/io/exr_io.h"

using namespace aaf;

namespace {

float attribute(const AovSet &aovs, const char *name) {
    const auto it = aovs.attributes.find(name);
    if (it == aovs.attributes.end() || !std::get_if<float>(&it->second))
        throw InputError(std::string("render lacks attribute ") + name);
    return std::get<float>(it->second);
}

std::vector<ConstPlaneView> planes(const AovSet &aovs, const ChannelMap &names, Role role) {
    std::vector<ConstPlaneView> out;
    for (const std::string &name : names.channels(role)) out.push_back(aovs.channel(name));
    return out;
}

double percent(long part, long whole) {
    return whole > 0 ? 100.0 * double(part) / double(whole) : 0.0;
}

}  // namespace

int main(int argc, char **argv) {
    CLI::App app{"Where aaf filter maaf6 uses the partition on a maaf6 render, and why not elsewhere"};
    std::string input;
    Maaf6FilterParams params;
    app.add_option("input", input, "A render of `aaf render SCENE --aovs maaf6`")->required();
    app.add_option("--k", params.k, "As aaf filter maaf6 --k")->capture_default_str();
    app.add_option("--max-radius", params.max_radius_px, "As aaf filter maaf6 --max-radius")
        ->capture_default_str();
    app.add_option("--band-spp", params.band_spp, "As aaf filter maaf6 --band-spp")->capture_default_str();
    double indirect_band_spp = 128;
    app.add_option("--indirect-band-spp", indirect_band_spp, "As aaf filter maaf6 --indirect-band-spp")
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    try {
        const AovSet aovs = io::read_aovs(input);
        const ChannelMap names;
        Maaf6SharedInputs shared;
        const std::vector<ConstPlaneView> wedge = planes(aovs, names, roles::Maaf6Wedge);
        shared.u_min = wedge.at(4);
        shared.u_max = wedge.at(5);
        shared.omega_x = wedge.at(6);
        const std::vector<ConstPlaneView> position = planes(aovs, names, Role::Position),
                                          normal = planes(aovs, names, Role::Normal);
        for (std::size_t c = 0; c < 3; ++c) {
            shared.position[c] = position.at(c);
            shared.normal[c] = normal.at(c);
        }
        shared.object_id = aovs.channel(names.channel(Role::ObjectId));
        shared.pixel_size = aovs.channel(names.channel(Role::PixelSize));
        shared.samples = aovs.channel(names.channel(roles::Maaf6Spp));
        shared.omega_u_max = double(attribute(aovs, attr::kMaaf6OmegaLens));
        std::printf(
            "%s, k %g, max radius %d px: filtered pixels of each layer by the reasons for the central "
            "filter\n",
            input.c_str(), params.k, params.max_radius_px);
        std::printf("%-9s %8s %8s %8s | %9s | %9s %9s %9s %9s %9s %9s %9s %9s | %9s\n", "layer", "backgr.",
                    "no wedge", "filtered", "widened", "partition", "a", "b", "a+b", "c", "a+c", "b+c",
                    "a+b+c", "cut");
        struct LayerSpec {
            const char *name;
            Role sums, weights;
            std::size_t wedge_channel;
            const char *omega;
        };
        for (const LayerSpec &spec : {LayerSpec{"direct", roles::Maaf6DirectSums, roles::Maaf6DirectWeights,
                                                0, attr::kMaaf6OmegaDirect},
                                      LayerSpec{"indirect", roles::Maaf6IndirectSums,
                                                roles::Maaf6IndirectWeights, 2, attr::kMaaf6OmegaIndirect}}) {
            Maaf6LayerInputs layer;
            layer.sums = planes(aovs, names, spec.sums);
            layer.weights = planes(aovs, names, spec.weights);
            layer.y_min = wedge.at(spec.wedge_channel);
            layer.y_max = wedge.at(spec.wedge_channel + 1);
            layer.omega_y_max = double(attribute(aovs, spec.omega));
            Maaf6FilterParams layer_params = params;
            if (spec.wedge_channel == 2) layer_params.band_spp = indirect_band_spp;
            const Maaf6PartitionCensus census = maaf6_partition_census(layer, shared, layer_params);
            std::printf("%-9s %8ld %8ld %8ld | %8.1f%% |", spec.name, census.background, census.no_wedge,
                        census.filtered, percent(census.band_widened, census.filtered));
            for (long count : census.by_reasons) std::printf(" %8.1f%%", percent(count, census.filtered));
            std::printf(" | %8.1f%%\n", percent(census.window_cut, census.filtered));
        }
    } catch (const std::exception &e) {
        std::cerr << "maaf6_census: error: " << e.what() << "\n";
        return 3;
    }
    return 0;
}
