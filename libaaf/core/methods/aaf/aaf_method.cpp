// Axis-Aligned Filtering of soft shadows (Mehta, Wang, Ramamoorthi 2012) as a
// registered method: its declaration (roles, parameters) and the wiring from
// the images to aaf_filter().
#include <cmath>
#include <limits>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/kernels/shadow_composition.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/methods/aaf/aaf_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/frame_allocator.h"
#include "aaf/core/util/parallel.h"
#include "aaf_method_inputs.h"

namespace aaf {

namespace {

/// Another renderer's pass of the key light, filtered with AAF's widths and
/// rejection together with the visibility (into `filtered_visibility`), in
/// one gather: each tap's weight is computed once for the four channels, and
/// as each channel's sums are its own, the bits are those of two gathers.
/// The pass is demodulated by the albedo where the frame has one, so that
/// texture is not blurred, and modulated back. A non-finite value is read as
/// 0, so it cannot spread (it stays in its own pixel's beauty).
void filter_visibility_and_pass(const MethodImages &images, const GatherGuides &guides,
                                const AafParams &params, ConstPlaneView visibility,
                                PlaneView filtered_visibility, const std::array<ConstPlaneView, 3> &pass,
                                const std::array<PlaneView, 3> &filtered) {
    const int width = images.width(), height = images.height();
    const std::size_t count = std::size_t(width) * std::size_t(height);
    const bool albedo = images.has(Role::Albedo);
    std::array<ConstPlaneView, 3> reflectance;
    if (albedo)
        for (std::size_t c = 0; c < 3; ++c) reflectance[c] = images.input(Role::Albedo, c);
    std::array<FramePlane<float>, 3> demodulated;
    for (FramePlane<float> &plane : demodulated) plane.resize(count);
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const float v = visibility(x, y);
            filtered_visibility(x, y) = std::isfinite(v) ? v : 0.0f;
        }
        for (std::size_t c = 0; c < 3; ++c) {
            float *const row = demodulated[c].data() + std::size_t(y) * std::size_t(width);
            for (int x = 0; x < width; ++x) {
                const float a = albedo ? reflectance[c](x, y) : 1.0f;
                const float value = a > 0 ? pass[c](x, y) / a : pass[c](x, y);
                row[x] = std::isfinite(value) ? value : 0.0f;
            }
        }
    });
    std::vector<ConstPlaneView> sources{filtered_visibility};
    std::vector<PlaneView> outputs{filtered_visibility};
    for (std::size_t c = 0; c < 3; ++c) {
        sources.push_back(plane_view<const float>(demodulated[c].data(), width, height));
        outputs.push_back(filtered[c]);
    }
    aaf_gather(guides, params, sources, outputs);
    if (!albedo) return;
    parallel_for_rows(height, [&](int y) {
        for (std::size_t c = 0; c < 3; ++c)
            for (int x = 0; x < width; ++x) {
                const float a = reflectance[c](x, y);
                if (a > 0) filtered[c](x, y) *= a;
            }
    });
}

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The parameters, each bound to its AafParams member: AafParams' defaults (AAF Sec. 6) and
/// AafParams::validate()'s ranges.
ParameterDeclarations<AafParams> declare_aaf_parameters() {
    using P = AafParams;
    return std::move(
        ParameterDeclarations<P>("aaf")
            .real("mu", &P::mu, "", "Filter scale for consistency, beta ~ 1/mu (AAF Sec. 5.2)", 0, kInf,
                  /*min_open=*/true)
            .flag("mu_from_spp", &P::mu_from_spp,
                  "Require the spp input: per pixel, raise mu until AAF Eq. 21's rate equals the samples "
                  "taken (consistency, AAF Sec. 5.2; the default whenever spp is given)")
            .flag("fixed_mu", &P::fixed_mu,
                  "One mu everywhere, ignoring the spp input (AAF Eq. 13 as printed; not consistent)")
            .choice(
                "light_bandlimit", &P::light_bandlimit,
                {{"sigma", LightBandlimit::Sigma},
                 {"equivalent_width", LightBandlimit::EquivalentWidth},
                 {"spectrum", LightBandlimit::Spectrum}},
                "Light band-limit 1/sigma_b of AAF Sec. 4.1: sigma (the paper's, the profile's sigma) or, "
                "for the Gaussian truncated at the light's edges, equivalent_width (the spectrum's area) "
                "or spectrum (falls to exp(-1/2) where the truncated profile's does); the plan (aaf "
                "plan, render --adaptive) must use the same")
            .choice("light_axes", &P::light_axes,
                    {{"per_axis", AafLightAxes::PerAxis}, {"shortest", AafLightAxes::Shortest}},
                    "per_axis: each light axis its own band-limit, an anisotropic Gaussian in the light's "
                    "plane; shortest: the sharper axis's for both (isotropic); the plan must use the same")
            .real("k", &P::k, "", "Gaussian spread factor of AAF Eq. 13", 0, kInf, /*min_open=*/true)
            .real("alpha", &P::alpha, "", "Occluder bandlimit over pixel bandlimit (AAF Eq. 5)", 0, 1,
                  /*min_open=*/true)
            .real("normal_threshold", &P::normal_threshold_deg, "degrees",
                  "Reject taps whose normal turns more", 0, 180)
            .integer("fill_radius", &P::fill_radius_px, "pixels",
                     "Radius to borrow occluder distances (AAF Sec. 6)", 0, 1 << 16)
            .integer("max_radius", &P::max_radius_px, "pixels", "Largest filter radius", 0, 1 << 16)
            .real("fixed_beta", &P::fixed_beta_m, "metres",
                  "Non-adaptive baseline of AAF Fig. 6: this beta everywhere AAF filters; 0 = AAF Eq. 13", 0)
            .choice("filter", &P::mode,
                    {{"separable", AafFilterMode::Separable}, {"2d", AafFilterMode::Exact2D}},
                    "separable: two 1D passes (AAF Sec. 6); 2d: exact 2D gather of AAF Eq. 10, to measure "
                    "the approximation")
            .choice("borders", &P::symmetric_borders, {{"symmetric", true}, {"clip", false}},
                    "symmetric: near the image edge the window shrinks on both sides and stays centred; "
                    "clip: cut on the edge side only (one-sided, biased on gradients)")
            .choice("light_distance", &P::light_distance,
                    {{"ray", AafLightDistance::AlongLightDirection},
                     {"plane", AafLightDistance::OrthogonalProjection},
                     {"guarded", AafLightDistance::Guarded}},
                    "Tap distance in the light's plane: ray (slid along the direction to the light onto the "
                    "light-parallel plane first), plane (AAF Eq. 12's orthogonal projection) or guarded "
                    "(plane, and ray where a receiver is within 6 degrees of perpendicular to the light's "
                    "plane)")
            .choice("pixel_footprint", &P::projected_pixel, {{"receiver", false}, {"projected", true}},
                    "Pixel size d of the pixel band-limit 1/d (AAF Eq. 6, 15): the receiver's own (the "
                    "paper's) or projected orthogonally onto the light's plane like the plane distances; "
                    "the plan must use the same"));
}

AafParams params_from(const ParameterSet &set) {
    return aaf_parameter_declarations().read(set);
}

class AafMethod final : public Method {
  public:
    AafMethod() {
        info_.name = "aaf";
        info_.title = "AAF";
        info_.summary = "Axis-Aligned Filtering of soft shadows (Mehta et al. 2012)";
        info_.reference =
            "Mehta, Wang, Ramamoorthi: Axis-Aligned Filtering for Interactive Sampled Soft Shadows, 2012";
        info_.roles.declared = aaf_roles();
        info_.roles.synonyms = {{roles::FilterWidth, "aaf 0.1", {"aaf.beta"}}};
        info_.roles.required = {Role::Visibility, Role::D1,        Role::D2Min,
                                Role::D2Max,      Role::Position,  Role::Normal,
                                Role::ObjectId,   Role::PixelSize, Role::Unshadowed};
        info_.roles.optional = {Role::SamplesPerPixel, Role::Albedo};
        for (Role role : shadow_composition_roles())
            if (role != Role::Visibility) info_.roles.optional.push_back(role);
        info_.roles.outputs = {Role::FilteredVisibility, roles::FilterWidth, Role::Beauty};
        info_.roles.widths = {roles::FilterWidth};
        // The slopes' extremes (AAF Eq. 4) over more frames' samples: widths that hold still.
        info_.roles.window_widths = {{Role::D2Min, Role::D2Min, {WindowExtreme::Min}},
                                     {Role::D2Max, Role::D2Max, {WindowExtreme::Max}}};
        info_.roles.filtered = {{Role::Visibility, Role::FilteredVisibility}};
        info_.parameters = aaf_parameter_declarations().infos();
        info_.required_attributes = light_attribute_names();
        // AAF for soft shadows, defocus and indirect light together is maaf6's
        // central filter alone, with its own widths per effect (MAAF Sec. 6.2's
        // baseline, after MYRD14).
        info_.delegates = {{"maaf6", {{"pairs", "1"}}, "a combined-effects render"}};
    }

    const MethodInfo &info() const override { return info_; }

    void check_parameters(const ParameterSet &parameters) const override {
        params_from(parameters).validate();
    }

    std::vector<Role> roles_needed(const ParameterSet &parameters) const override {
        std::vector<Role> roles = info_.roles.required;
        if (params_from(parameters).mu_from_spp) roles.push_back(Role::SamplesPerPixel);
        return roles;
    }

    void run(const MethodImages &images, const ParameterSet &parameters, Progress &progress) const override {
        const AafParams params = params_from(parameters);
        AafInputs in = aaf_geometry_inputs(images);
        in.visibility = images.input(Role::Visibility);
        if (params.mu_from_spp && !images.has(Role::SamplesPerPixel))
            throw InputError("mu from spp needs the 'spp' input (channel " +
                             images.channel_names(Role::SamplesPerPixel) + ")");
        // Consistency by default (AAF Sec. 5.3): the filter follows the samples taken when they are known.
        if (!params.fixed_mu && images.has(Role::SamplesPerPixel))
            in.spp = images.input(Role::SamplesPerPixel);
        AafOutputs out;
        out.filtered_visibility = images.output(Role::FilteredVisibility);
        out.beta_m = images.output(roles::FilterWidth);
        const LightPlane light = read_light_attributes(images.attributes());
        const auto has = [&](Role role) { return images.has(role); };
        const bool swaps_pass =
            shadow_beauty(images.attributes(), has, images.composition(), true) == ShadowBeauty::PassSwapped;
        {
            // aaf_filter() in two steps: where the beauty swaps in a pass of
            // the key light, the guides filter it with the visibility.
            const GatherGuides guides = aaf_gather_guides(in, light, params, out.beta_m);
            if (swaps_pass)
                filter_visibility_and_pass(images, guides, params, in.visibility, out.filtered_visibility,
                                           {images.input(Role::KeyLight, 0), images.input(Role::KeyLight, 1),
                                            images.input(Role::KeyLight, 2)},
                                           {images.output(Role::Beauty, 0), images.output(Role::Beauty, 1),
                                            images.output(Role::Beauty, 2)});
            else
                aaf_filter_visibility(guides, params, in.visibility, out.filtered_visibility);
        }  // the guides are freed before the beauty's planes are made
        progress.report(0.9);
        // The pass is already filtered, in the beauty's planes.
        const PassFilter filter_pass = [](const std::array<ConstPlaneView, 3> &,
                                          const std::array<PlaneView, 3> &) {};
        compose_shadowed_beauty(images, out.filtered_visibility, filter_pass);
    }

    std::string composition_note(const std::map<std::string, AttributeValue> &attributes,
                                 const std::function<bool(Role)> &has,
                                 Composition composition) const override {
        return shadow_beauty_note(shadow_beauty(attributes, has, composition, true), info_.title, true);
    }

  private:
    MethodInfo info_;
};

}  // namespace

std::unique_ptr<Method> make_aaf_method() {
    return std::make_unique<AafMethod>();
}

const ParameterDeclarations<AafParams> &aaf_parameter_declarations() {
    static const ParameterDeclarations<AafParams> declarations = declare_aaf_parameters();
    return declarations;
}

const std::vector<std::string> &aaf_plan_parameter_names() {
    static const std::vector<std::string> names = {"mu", "light_bandlimit", "light_axes", "pixel_footprint"};
    return names;
}

ParameterSet aaf_parameter_set(const AafParams &params) {
    return aaf_parameter_declarations().write(params);
}

std::vector<std::string> aaf_parameter_defaults_read_back_differently() {
    return aaf_parameter_declarations().defaults_read_back_differently();
}

AovSet aaf_filter_aovs(const AovSet &input, const ChannelMap &channels, const AafParams &params) {
    return filter_aovs(find_method("aaf"), input, channels, aaf_parameter_set(params));
}

}  // namespace aaf
