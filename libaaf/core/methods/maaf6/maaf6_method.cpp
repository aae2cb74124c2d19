// MAAF for combined effects (Wu et al. 2017, Sec. 6.2): soft shadows,
// defocus and one-bounce indirect light of a maaf6 render, direct and
// indirect filtered apart with their own wedges, then summed.
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/methods/maaf/maaf_roles.h"
#include "aaf/core/methods/maaf6/maaf6_components.h"
#include "aaf/core/methods/maaf6/maaf6_filter.h"
#include "aaf/core/methods/maaf6/maaf6_roles.h"
#include "aaf/core/util/error.h"

namespace aaf {

namespace {

template <typename T>
T header_value(const MethodImages &images, const char *name) {
    const auto it = images.attributes().find(name);
    if (it == images.attributes().end())
        throw InputError(std::string("missing header attribute '") + name + "'");
    const T *value = std::get_if<T>(&it->second);
    if (!value) throw InputError(std::string("header attribute '") + name + "' has the wrong type");
    return *value;
}

/// The filter's parameters and the indirect layer's own band_spp.
struct Maaf6Settings : Maaf6FilterParams {
    double indirect_band_spp = 128;
};

/// The parameters, each bound to its Maaf6Settings member (the header gives the rest).
const ParameterDeclarations<Maaf6Settings> &maaf6_parameters() {
    using P = Maaf6Settings;
    static const auto declarations = std::move(
        ParameterDeclarations<P>("maaf6")
            .choice("pairs", &P::pairs_used, {{"all", kMaafContractPairs}, {"1", 1}},
                    "Filter pairs N per 3D subspace: all of the sums' (N = 3, 25 filters in 6D) or 1, the "
                    "central axis-aligned filter alone (AAF for combined effects, MYRD14)")
            .choice("pair_weights", &P::pair_weights,
                    {{"fitted", Maaf6PairWeights::Fitted},
                     {"eq10", Maaf6PairWeights::Eq10},
                     {"one", Maaf6PairWeights::One},
                     {"light", Maaf6PairWeights::Light}},
                    "mu_p of the offset pairs: fitted: least squares so that the filter passes the sampling "
                    "density's spectrum along the wedge, as the light integral does (not in the paper; "
                    "measured better than MAAF Eq. 10 on room, see its README); eq10: MAAF Eq. 10, the "
                    "paper's; one: mu_p = 1; light: MAAF Eq. 10 times the Gaussian light model's spectrum at "
                    "the pair's y "
                    "centre")
            .real("k", &P::k, "",
                  "Width scale: each component's Fourier std is its half-width divided by k (as `aaf filter "
                  "maaf --k`; 1 = the paper's reading, measured best on room for both N = 3 and N = 1)",
                  0.01, 100)
            .real("normal_threshold", &P::normal_threshold_deg, "degrees",
                  "Reject taps whose normal turns more (MAAF Sec. 6.2)", 0, 180)
            .integer("max_radius", &P::max_radius_px, "pixels", "Largest filter radius", 0, 1 << 12)
            .choice("filter", &P::vectorised, {{"vector", true}, {"scalar", false}},
                    "vector: each tap for a vector of centres at once, in float; scalar: one centre at a "
                    "time in double, the reference the vector filter is tested against")
            .real("band_spp", &P::band_spp, "spp",
                  "Samples per pixel at which the direct layer's light and lens bands are MAAF Sec. 3's; "
                  "past it they widen as sqrt(spp / band_spp), the pixel band with them, and the pixel gets "
                  "the axis-aligned filter, so the filter narrows as samples are added and converges to the "
                  "reference (AAF Sec. 5.2's consistency; 16 = the first pass); 0 = the paper's fixed bands, "
                  "whose bias stays whatever the samples",
                  0)
            .real("indirect_band_spp", &P::indirect_band_spp, "spp",
                  "As band_spp, for the indirect layer: its noise is several times the direct layer's at "
                  "equal samples, so its filter stays wide for longer (on room fixed bands were best for it "
                  "up to 256 spp; 128 is the smallest that lost nothing up to 128 spp, see its README); 0 = "
                  "fixed bands",
                  0));
    return declarations;
}

/// How maaf6's beauty is made.
enum class Maaf6Beauty {
    Sum,        ///< filtered direct plus indirect (Composition::Paper, or no input beauty)
    Corrected,  ///< the input beauty less the render's two means plus the filtered ones
    Kept,       ///< the input beauty as it was: it is not the sum of the two means
};

Maaf6Beauty maaf6_beauty(const std::map<std::string, AttributeValue> &attributes,
                         const std::function<bool(Role)> &has, Composition composition) {
    if (composition == Composition::Paper || !has(Role::Beauty)) return Maaf6Beauty::Sum;
    return beauty_holds_exactly(attributes, beauty_holds::kMaaf6) && has(roles::Maaf6Direct) &&
                   has(roles::Maaf6Indirect)
               ? Maaf6Beauty::Corrected
               : Maaf6Beauty::Kept;
}

/// MAAF Sec. 6.2: direct and indirect filtered apart, then summed, in place
/// of the render's own sum in its beauty.
void write_beauty(const MethodImages &images) {
    const auto has = [&](Role role) { return images.has(role); };
    const Maaf6Beauty how = maaf6_beauty(images.attributes(), has, images.composition());
    for (std::size_t c = 0; c < 3; ++c) {
        const PlaneView beauty = images.output(Role::Beauty, c);
        const ConstPlaneView direct = images.output(roles::Maaf6Direct, c);
        const ConstPlaneView indirect = images.output(roles::Maaf6Indirect, c);
        const bool sum = how == Maaf6Beauty::Sum;
        const ConstPlaneView in = sum ? ConstPlaneView{} : images.input(Role::Beauty, c);
        const bool corrected = how == Maaf6Beauty::Corrected;
        const ConstPlaneView noisy_direct =
            corrected ? images.input(roles::Maaf6Direct, c) : ConstPlaneView{};
        const ConstPlaneView noisy_indirect =
            corrected ? images.input(roles::Maaf6Indirect, c) : ConstPlaneView{};
        for (int y = 0; y < images.height(); ++y)
            for (int x = 0; x < images.width(); ++x) {
                const float filtered = direct(x, y) + indirect(x, y);
                if (sum)
                    beauty(x, y) = filtered;
                else if (corrected)  // in double: the two layers' sums may pass float's range
                    beauty(x, y) = float(
                        (double(in(x, y)) - (double(noisy_direct(x, y)) + double(noisy_indirect(x, y)))) +
                        (double(direct(x, y)) + double(indirect(x, y))));
                else
                    beauty(x, y) = in(x, y);
            }
    }
}

class Maaf6Method final : public Method {
  public:
    Maaf6Method() {
        info_.name = "maaf6";
        info_.title = "MAAF 6D";
        info_.summary =
            "MAAF for combined soft shadows, defocus and indirect light (Wu et al. 2017, Sec. 6.2); --pairs "
            "1 is "
            "the axis-aligned baseline (MYRD14)";
        info_.reference =
            "Wu, Yan, Kuznetsov, Ramamoorthi: Multiple Axis-Aligned Filters for Rendering of Combined "
            "Distribution Effects, 2017";
        info_.roles.declared = maaf6_roles();
        info_.roles.required = {roles::Maaf6DirectSums,   roles::Maaf6DirectWeights,
                                roles::Maaf6IndirectSums, roles::Maaf6IndirectWeights,
                                roles::Maaf6Wedge,        roles::Maaf6Spp,
                                Role::Position,           Role::Normal,
                                Role::ObjectId,           Role::PixelSize};
        // The render's own means of the two layers, replaced by the filtered ones.
        info_.roles.optional = {Role::Beauty, roles::Maaf6Direct, roles::Maaf6Indirect,
                                roles::Maaf6WindowWedge};
        info_.roles.outputs = {roles::Maaf6Direct, roles::Maaf6Indirect, Role::Beauty};
        // The wedges' extremes over a temporal window (the pixel band aside): widths that hold still.
        using E = WindowExtreme;
        info_.roles.window_widths = {
            {roles::Maaf6Wedge,
             roles::Maaf6WindowWedge,
             {E::MinNonNegative, E::Max, E::MinNonNegative, E::Max, E::Min, E::Max, std::nullopt}}};
        info_.parameters = maaf6_parameters().infos();
        info_.required_attributes = light_attribute_names();
        for (const char *name :
             {attr::kMaaf6Pairs, attr::kMaaf6OmegaDirect, attr::kMaaf6OmegaIndirect, attr::kMaaf6OmegaLens})
            info_.required_attributes.push_back(name);
    }

    const MethodInfo &info() const override { return info_; }

    void run(const MethodImages &images, const ParameterSet &parameters, Progress &progress) const override {
        const int pairs = header_value<int>(images, attr::kMaaf6Pairs);
        if (pairs != kMaafContractPairs)
            throw InputError(
                "header attribute '" + std::string(attr::kMaaf6Pairs) + "' is " + std::to_string(pairs) +
                "; the maaf6 channels of the contract hold N = " + std::to_string(kMaafContractPairs));
        Maaf6SharedInputs shared;
        shared.u_min = images.input(roles::Maaf6Wedge, 4);
        shared.u_max = images.input(roles::Maaf6Wedge, 5);
        shared.omega_x = images.input(roles::Maaf6Wedge, 6);
        const bool window = images.has(roles::Maaf6WindowWedge);
        if (window) {
            shared.window_u_min = images.input(roles::Maaf6WindowWedge, 4);
            shared.window_u_max = images.input(roles::Maaf6WindowWedge, 5);
        }
        for (std::size_t c = 0; c < 3; ++c) {
            shared.position[c] = images.input(Role::Position, c);
            shared.normal[c] = images.input(Role::Normal, c);
        }
        shared.object_id = images.input(Role::ObjectId);
        shared.pixel_size = images.input(Role::PixelSize);
        shared.samples = images.input(roles::Maaf6Spp);
        shared.omega_u_max = double(header_value<float>(images, attr::kMaaf6OmegaLens));
        if (!(shared.omega_u_max >= 0) || !std::isfinite(shared.omega_u_max))
            throw InputError("header attribute '" + std::string(attr::kMaaf6OmegaLens) +
                             "' must be finite and not negative (0: a pinhole)");
        const Maaf6Settings settings = maaf6_parameters().read(parameters);
        Maaf6FilterParams params = settings;
        params.stored_pairs = pairs;
        params.pairs_used = settings.pairs_used == 1 ? 1 : pairs;
        const double indirect_band_spp = settings.indirect_band_spp;
        const LightPlane light = read_light_attributes(images.attributes());
        // The lens is a uniform disc of radius A = 4 / Omega_u^max (the contract's MAAF Sec. 3 band, L = A).
        if (shared.omega_u_max > 0)
            shared.lens_density = {DensityShape::Semicircle, 4.0 / shared.omega_u_max, 1.0};
        const int channels = maaf6_channel_count(pairs);

        struct Layer {
            Role sums, weights, output;
            std::size_t wedge_channel;
            const char *omega;
        };
        const Layer layers[2] = {{roles::Maaf6DirectSums, roles::Maaf6DirectWeights, roles::Maaf6Direct, 0,
                                  attr::kMaaf6OmegaDirect},
                                 {roles::Maaf6IndirectSums, roles::Maaf6IndirectWeights, roles::Maaf6Indirect,
                                  2, attr::kMaaf6OmegaIndirect}};
        for (int l = 0; l < 2; ++l) {
            const Layer &spec = layers[l];
            Maaf6LayerInputs layer;
            for (int c = 0; c < 3 * channels; ++c)
                layer.sums.push_back(images.input(spec.sums, std::size_t(c)));
            for (int c = 0; c < channels; ++c)
                layer.weights.push_back(images.input(spec.weights, std::size_t(c)));
            layer.y_min = images.input(roles::Maaf6Wedge, spec.wedge_channel);
            layer.y_max = images.input(roles::Maaf6Wedge, spec.wedge_channel + 1);
            if (window) {
                layer.window_y_min = images.input(roles::Maaf6WindowWedge, spec.wedge_channel);
                layer.window_y_max = images.input(roles::Maaf6WindowWedge, spec.wedge_channel + 1);
            }
            layer.omega_y_max = double(header_value<float>(images, spec.omega));
            layer.y_density =
                l == 0 ? light_sample_density(light) : SampleDensity{DensityShape::CosineLobe, 1.0, 1.0};
            if (!(layer.omega_y_max > 0) || !std::isfinite(layer.omega_y_max))
                throw InputError("header attribute '" + std::string(spec.omega) +
                                 "' must be positive and finite");
            const std::array<PlaneView, 3> out = {
                images.output(spec.output, 0), images.output(spec.output, 1), images.output(spec.output, 2)};
            Maaf6FilterParams layer_params = params;
            if (l == 1) layer_params.band_spp = indirect_band_spp;
            maaf6_filter_layer(layer, shared, light, layer_params, out);
            progress.report(0.45 * (l + 1));
        }
        write_beauty(images);
    }

    std::string composition_note(const std::map<std::string, AttributeValue> &attributes,
                                 const std::function<bool(Role)> &has,
                                 Composition composition) const override {
        if (maaf6_beauty(attributes, has, composition) != Maaf6Beauty::Kept) return {};
        return "R,G,B left as rendered: the beauty does not hold maaf6.direct + maaf6.indirect (no " +
               std::string(attr::kBeauty) + " = " + beauty_holds::kMaaf6 +
               "); the estimate is in maaf6.direct and maaf6.indirect, or --compose paper writes their sum "
               "to R,G,B";
    }

  private:
    MethodInfo info_;
};

}  // namespace

std::unique_ptr<Method> make_maaf6_method() {
    return std::make_unique<Maaf6Method>();
}

std::vector<std::string> maaf6_parameter_defaults_read_back_differently() {
    return maaf6_parameters().defaults_read_back_differently();
}

}  // namespace aaf
