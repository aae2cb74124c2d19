// Multiple Axis-Aligned Filtering of soft shadows (Wu, Yan, Kuznetsov,
// Ramamoorthi 2017) as a registered method: its declaration (roles,
// parameters) and the wiring from the images to maaf_filter().
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/kernels/shadow_composition.h"
#include "aaf/core/methods/maaf/maaf_accumulation.h"
#include "aaf/core/methods/maaf/maaf_filter.h"
#include "aaf/core/methods/maaf/maaf_roles.h"
#include "aaf/core/util/error.h"

namespace aaf {

namespace {

/// The parameters, each bound to its MaafParams member (the header gives omega_y_max).
const ParameterDeclarations<MaafParams> &maaf_parameters() {
    using P = MaafParams;
    static const auto declarations = std::move(
        ParameterDeclarations<P>("maaf")
            .choice(
                "pairs", &P::pairs_used, {{"all", 0}, {"1", 1}},
                "Filter pairs N per 2D subspace: all of the sums' (the tracer writes N = 3, 25 filters in "
                "4D) or 1, the central filter alone (AAF)")
            .choice(
                "pair_weights", &P::pair_weights,
                {{"eq10", MaafPairWeights::Eq10},
                 {"one", MaafPairWeights::One},
                 {"light", MaafPairWeights::Light},
                 {"fitted", MaafPairWeights::Fitted}},
                "The offset pairs' weights mu_p: eq10, MAAF Eq. 10 as printed; one, mu_p = 1; light, Eq. 10 "
                "times the light's spectrum at the pair's y centre; fitted, fitted per slope ratio to the "
                "light's spectrum along the wedge (measured: README beside the method)")
            .real("k", &P::k, "",
                  "Width scale: each component's Fourier-domain std is k times its half-width sigma_x^p (1 = "
                  "the paper's reading of MAAF Eq. 8-9; 3 = AAF's k, N = 1 then equals AAF's default filter)",
                  0.01, 100)
            .real("normal_threshold", &P::normal_threshold_deg, "degrees",
                  "Reject taps whose normal turns more (MAAF Sec. 6.2)", 0, 180)
            .integer("max_radius", &P::max_radius_px, "pixels", "Largest filter radius", 0, 1 << 16)
            .real("band_spp", &P::band_spp, "spp",
                  "Samples per pixel at which the light and pixel bands are the render's; past it (the spp "
                  "input) they widen as sqrt(spp / band_spp) and the pixel gets the central filter, so the "
                  "filter narrows as samples are added and converges to the reference (AAF Sec. 5.2's "
                  "consistency; 16 = the tracer's first pass); 0 = the render's bands whatever the samples "
                  "(the paper's fixed width, whose bias stays)",
                  0)
            .choice("filter", &P::separable, {{"separable", true}, {"2d", false}},
                    "separable: two 1D passes per component pair (complex exponentials, as AAF Sec. 6 "
                    "separates); 2d: every tap of MAAF Eq. 21, to measure the approximation"));
    return declarations;
}

template <typename T>
T header_value(const MethodImages &images, const char *name) {
    const auto it = images.attributes().find(name);
    if (it == images.attributes().end())
        throw InputError(std::string("missing header attribute '") + name + "'");
    const T *value = std::get_if<T>(&it->second);
    if (!value) throw InputError(std::string("header attribute '") + name + "' has the wrong type");
    return *value;
}

class MaafMethod final : public Method {
  public:
    MaafMethod() {
        info_.name = "maaf";
        info_.title = "MAAF";
        info_.summary = "Multiple Axis-Aligned Filters for soft shadows (Wu et al. 2017)";
        info_.reference =
            "Wu, Yan, Kuznetsov, Ramamoorthi: Multiple Axis-Aligned Filters for Rendering of Combined "
            "Distribution Effects, 2017";
        info_.roles.declared = maaf_roles();
        info_.roles.required = {
            roles::MaafValueSums, roles::MaafUnoccludedSums, roles::MaafWedge, Role::Position, Role::Normal,
            Role::ObjectId,       Role::PixelSize,           Role::Unshadowed};
        info_.roles.optional = shadow_composition_roles();
        info_.roles.optional.push_back(Role::SamplesPerPixel);  // the width follows the samples (band_spp)
        info_.roles.optional.push_back(roles::MaafWindowWedge);
        info_.roles.outputs = {Role::FilteredVisibility, Role::Beauty};
        // The wedge's slopes over a temporal window (the bands aside): widths that hold still.
        info_.roles.window_widths = {{roles::MaafWedge,
                                      roles::MaafWindowWedge,
                                      {WindowExtreme::Min, WindowExtreme::Max, std::nullopt, std::nullopt}}};
        info_.parameters = maaf_parameters().infos();
        info_.required_attributes = light_attribute_names();
        info_.required_attributes.push_back(attr::kMaafPairs);
        info_.required_attributes.push_back(attr::kMaafOmegaYMax);
        // Soft shadows, defocus and indirect light in one render: the 6D filter (MAAF Sec. 6.2).
        info_.delegates = {{"maaf6", {}, "a combined-effects render"}};
    }

    const MethodInfo &info() const override { return info_; }

    void run(const MethodImages &images, const ParameterSet &parameters, Progress &progress) const override {
        const int pairs = header_value<int>(images, attr::kMaafPairs);
        if (pairs != kMaafContractPairs)
            throw InputError(
                "header attribute '" + std::string(attr::kMaafPairs) + "' is " + std::to_string(pairs) +
                "; the MAAF channels of the contract hold N = " + std::to_string(kMaafContractPairs));
        MaafInputs in;
        in.pairs = pairs;
        for (int c = 0; c < maaf_channel_count(pairs); ++c) {
            in.value_sums.push_back(images.input(roles::MaafValueSums, std::size_t(c)));
            in.unoccluded_sums.push_back(images.input(roles::MaafUnoccludedSums, std::size_t(c)));
        }
        in.s_min = images.input(roles::MaafWedge, 0);
        in.s_max = images.input(roles::MaafWedge, 1);
        in.omega_x_max = images.input(roles::MaafWedge, 2);
        if (images.has(roles::MaafWindowWedge)) {
            in.window_s_min = images.input(roles::MaafWindowWedge, 0);
            in.window_s_max = images.input(roles::MaafWindowWedge, 1);
        }
        for (std::size_t c = 0; c < 3; ++c) {
            in.position[c] = images.input(Role::Position, c);
            in.normal[c] = images.input(Role::Normal, c);
        }
        in.object_id = images.input(Role::ObjectId);
        in.pixel_size = images.input(Role::PixelSize);
        MaafParams params = maaf_parameters().read(parameters);
        if (params.band_spp > 0 && images.has(Role::SamplesPerPixel))
            in.samples = images.input(Role::SamplesPerPixel);
        params.omega_y_max_rad_per_m = double(header_value<float>(images, attr::kMaafOmegaYMax));
        params.light_density = light_sample_density(read_light_attributes(images.attributes()));
        if (!(params.omega_y_max_rad_per_m > 0) || !std::isfinite(params.omega_y_max_rad_per_m))
            throw InputError("header attribute '" + std::string(attr::kMaafOmegaYMax) + "' must be positive");
        const PlaneView filtered = images.output(Role::FilteredVisibility);
        maaf_filter(in, read_light_attributes(images.attributes()), params, filtered);
        progress.report(0.9);
        compose_shadowed_beauty(images, filtered);  // AAF Eq. 1, or the beauty corrected
    }

    std::string composition_note(const std::map<std::string, AttributeValue> &attributes,
                                 const std::function<bool(Role)> &has,
                                 Composition composition) const override {
        return shadow_beauty_note(shadow_beauty(attributes, has, composition, false), info_.title, false);
    }

  private:
    MethodInfo info_;
};

}  // namespace

std::unique_ptr<Method> make_maaf_method() {
    return std::make_unique<MaafMethod>();
}

std::vector<std::string> maaf_parameter_defaults_read_back_differently() {
    return maaf_parameters().defaults_read_back_differently();
}

}  // namespace aaf
