// Axis-Aligned Filtering of soft shadows (Mehta, Wang, Ramamoorthi 2012) as a
// registered method: its declaration (roles, parameters) and the wiring from
// the images to aaf_filter().
#include <limits>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/aaf_filter.h"
#include "aaf/core/error.h"
#include "aaf/core/filter_aovs.h"
#include "aaf/core/method_registry.h"
#include "aaf/core/shadow_composition.h"
#include "aaf_method_inputs.h"

namespace aaf {

namespace {

/// The parameters, with AafParams' defaults (AAF Sec. 6) and AafParams::validate()'s ranges.
std::vector<ParameterInfo> aaf_parameters() {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    return {
        ParameterInfo::real("mu", "2", "", "Filter scale for consistency, beta ~ 1/mu (AAF Sec. 5.2)", 0,
                            kInf,
                            /*min_open=*/true),
        ParameterInfo::flag("mu_from_spp",
                            "Require the spp input: per pixel, raise mu until AAF Eq. 21's rate equals the "
                            "samples taken (consistency, AAF Sec. 5.2; the default whenever spp is given)"),
        ParameterInfo::flag(
            "fixed_mu", "One mu everywhere, ignoring the spp input (AAF Eq. 13 as printed; not consistent)"),
        ParameterInfo::choice(
            "light_bandlimit", "sigma", {"sigma", "equivalent_width", "spectrum"},
            "Light band-limit 1/sigma_b of AAF Sec. 4.1: sigma (the paper's, the profile's sigma) or, "
            "for the Gaussian truncated at the light's edges, equivalent_width (the spectrum's area) "
            "or spectrum (falls to exp(-1/2) where the truncated profile's does); the plan (aaf "
            "plan, render --adaptive) must use the same"),
        ParameterInfo::choice("light_axes", "per_axis", {"per_axis", "shortest"},
                              "per_axis: each light axis its own band-limit, an anisotropic Gaussian in the "
                              "light's plane; shortest: the sharper axis's for both (isotropic); the plan "
                              "must use the same"),
        ParameterInfo::real("k", "3", "", "Gaussian spread factor of AAF Eq. 13", 0, kInf, /*min_open=*/true),
        ParameterInfo::real("alpha", "1", "", "Occluder bandlimit over pixel bandlimit (AAF Eq. 5)", 0, 1,
                            /*min_open=*/true),
        ParameterInfo::real("normal_threshold", "25", "degrees", "Reject taps whose normal turns more", 0,
                            180),
        ParameterInfo::integer("fill_radius", "5", "pixels",
                               "Radius to borrow occluder distances (AAF Sec. 6)", 0, 1 << 16),
        ParameterInfo::integer("max_radius", "64", "pixels", "Largest filter radius", 0, 1 << 16),
        ParameterInfo::real(
            "fixed_beta", "0", "metres",
            "Non-adaptive baseline of AAF Fig. 6: this beta everywhere AAF filters; 0 = AAF Eq. 13", 0),
        ParameterInfo::choice("filter", "separable", {"separable", "2d"},
                              "separable: two 1D passes (AAF Sec. 6); 2d: exact 2D gather of AAF Eq. 10, to "
                              "measure the approximation"),
        ParameterInfo::choice("borders", "symmetric", {"symmetric", "clip"},
                              "symmetric: near the image edge the window shrinks on both sides and stays "
                              "centred; clip: cut on the edge side only (one-sided, biased on gradients)"),
        ParameterInfo::choice(
            "light_distance", "ray", {"ray", "plane", "guarded"},
            "Tap distance in the light's plane: ray (slid along the direction to the light onto "
            "the light-parallel plane first), plane (AAF Eq. 12's orthogonal projection) or guarded "
            "(plane, and ray where a receiver is within 6 degrees of perpendicular to the light's "
            "plane)"),
        ParameterInfo::choice("pixel_footprint", "receiver", {"receiver", "projected"},
                              "Pixel size d of the pixel band-limit 1/d (AAF Eq. 6, 15): the receiver's own "
                              "(the paper's) or projected orthogonally onto the light's plane like the plane "
                              "distances; the plan must use the same"),
    };
}

AafParams params_from(const ParameterSet &set) {
    AafParams p;
    p.mu = set.get_float("mu");
    p.mu_from_spp = set.get_bool("mu_from_spp");
    p.fixed_mu = set.get_bool("fixed_mu");
    p.light_bandlimit = light_bandlimit_from_string(set.get_choice("light_bandlimit"));
    p.light_axes = light_axes_from_string(set.get_choice("light_axes"));
    p.k = set.get_float("k");
    p.alpha = set.get_float("alpha");
    p.normal_threshold_deg = set.get_float("normal_threshold");
    p.fill_radius_px = set.get_int("fill_radius");
    p.max_radius_px = set.get_int("max_radius");
    p.fixed_beta_m = set.get_float("fixed_beta");
    p.mode = set.get_choice("filter") == "2d" ? AafFilterMode::Exact2D : AafFilterMode::Separable;
    p.symmetric_borders = set.get_choice("borders") == "symmetric";
    const std::string distance = set.get_choice("light_distance");
    p.light_distance = distance == "plane" ? AafLightDistance::OrthogonalProjection
                       : distance == "ray" ? AafLightDistance::AlongLightDirection
                                           : AafLightDistance::Guarded;
    p.projected_pixel = set.get_choice("pixel_footprint") == "projected";
    return p;
}

class AafMethod final : public Method {
  public:
    AafMethod() {
        info_.name = "aaf";
        info_.title = "AAF";
        info_.summary = "Axis-Aligned Filtering of soft shadows (Mehta et al. 2012)";
        info_.reference =
            "Mehta, Wang, Ramamoorthi: Axis-Aligned Filtering for Interactive Sampled Soft Shadows, 2012";
        info_.roles.required = {Role::Visibility, Role::D1,        Role::D2Min,
                                Role::D2Max,      Role::Position,  Role::Normal,
                                Role::ObjectId,   Role::PixelSize, Role::Unshadowed};
        info_.roles.optional = {Role::SamplesPerPixel, Role::OtherLights};
        info_.roles.outputs = {Role::FilteredVisibility, Role::FilterWidth, Role::Beauty};
        info_.roles.filtered = {{Role::Visibility, Role::FilteredVisibility}};
        info_.parameters = aaf_parameters();
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
        out.beta_m = images.output(Role::FilterWidth);
        aaf_filter(in, read_light_attributes(images.attributes()), params, out);
        progress.report(0.9);
        compose_shadowed_beauty(images, out.filtered_visibility);  // AAF Eq. 1
    }

  private:
    MethodInfo info_;
};

}  // namespace

std::unique_ptr<Method> make_aaf_method() {
    return std::make_unique<AafMethod>();
}

ParameterSet aaf_parameter_set(const AafParams &params) {
    ParameterSet set("aaf", aaf_parameters());
    set.set("mu", double(params.mu));
    set.set("mu_from_spp", params.mu_from_spp);
    set.set("fixed_mu", params.fixed_mu);
    set.set("light_bandlimit", std::string(to_string(params.light_bandlimit)));
    set.set("light_axes", std::string(to_string(params.light_axes)));
    set.set("k", double(params.k));
    set.set("alpha", double(params.alpha));
    set.set("normal_threshold", double(params.normal_threshold_deg));
    set.set("fill_radius", double(params.fill_radius_px));
    set.set("max_radius", double(params.max_radius_px));
    set.set("fixed_beta", double(params.fixed_beta_m));
    set.set("filter", std::string(params.mode == AafFilterMode::Exact2D ? "2d" : "separable"));
    set.set("borders", std::string(params.symmetric_borders ? "symmetric" : "clip"));
    set.set("light_distance",
            std::string(params.light_distance == AafLightDistance::OrthogonalProjection  ? "plane"
                        : params.light_distance == AafLightDistance::AlongLightDirection ? "ray"
                                                                                         : "guarded"));
    set.set("pixel_footprint", std::string(params.projected_pixel ? "projected" : "receiver"));
    return set;
}

AovSet aaf_filter_aovs(const AovSet &input, const ChannelMap &channels, const AafParams &params) {
    return filter_aovs(find_method("aaf"), input, channels, aaf_parameter_set(params));
}

}  // namespace aaf
