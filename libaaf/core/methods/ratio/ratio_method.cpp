// The ratio estimator of shadowed direct light (Heitz, Hill, McGuire 2018)
// as a registered method: its declaration (roles, parameters) and the wiring
// from the images to the noise estimate, the denoisers, the composition and
// the temporal accumulation.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "../aaf/aaf_method_inputs.h"
#include "../builtin_methods.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/kernels/fixed_gaussian.h"
#include "aaf/core/kernels/gather.h"
#include "aaf/core/methods/aaf/aaf_filter.h"
#include "aaf/core/methods/ratio/ratio_bilateral.h"
#include "aaf/core/methods/ratio/ratio_composition.h"
#include "aaf/core/methods/ratio/ratio_noise_estimate.h"
#include "aaf/core/methods/ratio/ratio_roles.h"
#include "aaf/core/methods/ratio/ratio_temporal.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

struct RatioSettings {
    RatioEstimator estimator = RatioEstimator::Ratio;
    std::string denoiser = "bilateral";
    bool grey = false, summed = false, temporal = false;
    int noise_radius_px = 6;
    float sigma_per_noise_px = 3, max_sigma_px = 8, plane_sigma = 1, gaussian_sigma_px = 4,
          temporal_alpha = 0.2f;
    std::uint32_t seed = 0;
};

/// The parameters, each bound to its RatioSettings member.
const ParameterDeclarations<RatioSettings> &ratio_parameters() {
    using P = RatioSettings;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    static const auto declarations = std::move(
        ParameterDeclarations<P>("ratio")
            .choice("estimator", &P::estimator,
                    {{"ratio", RatioEstimator::Ratio},
                     {"stochastic", RatioEstimator::Stochastic},
                     {"control-variate", RatioEstimator::ControlVariate}},
                    "What is denoised: ratio, U x den(S_N) / den(U_N) (ratio estimator Eq. 25); stochastic, "
                    "den(S_N) (ratio estimator Eq. 10); control-variate, den(U - U_N + S_N) (ratio estimator "
                    "Eq. 11); same denoiser and widths")
            .text_choice(
                "denoiser", &P::denoiser, {"bilateral", "gaussian", "aaf"},
                "bilateral: the joint bilateral with sigma from the noise estimate (Sec. 4); gaussian: one "
                "fixed screen-space sigma (Fig. 7); aaf: AAF's per-pixel widths (needs the shadow group's "
                "d1/d2 and the key light's header; the key light's widths serve every light)")
            .flag("grey", &P::grey,
                  "One W per pixel from the luminance layers (ratio.S.Y / ratio.Un.Y, Sec. 3.4)")
            .flag("summed", &P::summed,
                  "Denoise the summed layers only, ignoring the per-light ratio.L<i>.* layers")
            .integer("noise_radius", &P::noise_radius_px, "pixels",
                     "Half length of the 4 lines of the noise estimate E (ratio estimator Eq. 29)", 1, 64)
            .real("sigma_per_noise", &P::sigma_per_noise_px, "pixels",
                  "Bilateral sigma = this x E (E: mean absolute second difference of W_N per pixel, ratio "
                  "estimator Eq. 29)",
                  0, kInf)
            .real("max_sigma", &P::max_sigma_px, "pixels", "Cap on the bilateral sigma", 0, 64)
            .real("plane_sigma", &P::plane_sigma, "pixel footprints",
                  "Bilateral plane weight: Gaussian of a tap's distance from the centre's tangent plane, in "
                  "pixel.size (scene scale) units",
                  0, kInf, /*min_open=*/true)
            .real("sigma", &P::gaussian_sigma_px, "pixels", "Width of --denoiser gaussian (Fig. 7 uses 4)", 0,
                  256)
            .integer("seed", &P::seed, "", "Seed of the noise estimate's per-pixel line rotation", 0, 1 << 30)
            .flag(
                "temporal", &P::temporal,
                "On a sequence: blend with the previous frame's output by reverse reprojection (motion AOV), "
                "rejecting disocclusions by plane distance and normal (Sec. 4.1)")
            .real("temporal_alpha", &P::temporal_alpha, "", "Weight of the current frame in the history", 0,
                  1,
                  /*min_open=*/true));
    return declarations;
}

RatioSettings settings_from(const ParameterSet &set) {
    const RatioSettings s = ratio_parameters().read(set);
    if (s.grey && s.estimator != RatioEstimator::Ratio)
        throw Error("ratio: --grey applies to --estimator ratio only");
    return s;
}

/// The scene scale plane distances are measured in: the PixelSize role, or
/// where a renderer wrote none, the diagonal of the finite positions' bounds
/// over the image's larger side (a typical pixel footprint).
std::vector<float> scene_scale_m(const MethodImages &images) {
    const int width = images.width(), height = images.height();
    std::vector<float> scale(std::size_t(width) * std::size_t(height), 0.0f);
    if (images.has(Role::PixelSize)) {
        const ConstPlaneView size = images.input(Role::PixelSize);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                scale[std::size_t(y) * std::size_t(width) + std::size_t(x)] = size(x, y);
        return scale;
    }
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float p[3] = {images.input(Role::Position, 0)(x, y), images.input(Role::Position, 1)(x, y),
                                images.input(Role::Position, 2)(x, y)};
            if (!std::isfinite(p[0] + p[1] + p[2])) continue;
            for (int c = 0; c < 3; ++c) {
                lo[c] = std::min(lo[c], p[c]);
                hi[c] = std::max(hi[c], p[c]);
            }
        }
    if (!(hi[0] >= lo[0])) return scale;  // no finite position: nothing is a surface
    const float diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
    const float footprint = diagonal > 0 ? diagonal / float(std::max(width, height)) : 1.0f;
    std::fill(scale.begin(), scale.end(), footprint);
    return scale;
}

/// Light `light`'s layers, or the summed ones for light -1.
RatioLayers layers_of(const MethodImages &images, int light, bool grey) {
    auto view = [&](Role role, std::size_t c) {
        return light < 0 ? images.input(role, c) : images.light_input(role, light, c);
    };
    auto has = [&](Role role) { return light < 0 ? images.has(role) : images.has_light(role, light); };
    const std::vector<Role> needed =
        grey ? std::vector<Role>{roles::RatioAnalytic, roles::RatioShadowedLuminance,
                                 roles::RatioUnshadowedLuminance}
             : std::vector<Role>{roles::RatioAnalytic, roles::RatioShadowed, roles::RatioUnshadowed};
    for (Role role : needed)
        if (!has(role))
            throw InputError(
                std::string("missing ratio input '") + role.key + "' (channels " +
                (light < 0 ? images.channel_names(role) : images.light_channel_names(role, light)) + ")");
    RatioLayers layers;
    for (std::size_t c = 0; c < 3; ++c) {
        layers.analytic[c] = view(roles::RatioAnalytic, c);
        if (grey) continue;
        layers.shadowed[c] = view(roles::RatioShadowed, c);
        layers.unshadowed[c] = view(roles::RatioUnshadowed, c);
    }
    if (grey) {
        layers.shadowed_y = view(roles::RatioShadowedLuminance, 0);
        layers.unshadowed_y = view(roles::RatioUnshadowedLuminance, 0);
    }
    return layers;
}

/// Rec. 709 luminance of three planes, non-finite read as 0.
std::vector<float> luminance(const std::array<ConstPlaneView, 3> &rgb) {
    const int width = rgb[0].width, height = rgb[0].height;
    std::vector<float> y_plane(std::size_t(width) * std::size_t(height));
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            float v = 0;
            const float weights[3] = {0.2126f, 0.7152f, 0.0722f};
            for (int c = 0; c < 3; ++c) v += std::isfinite(rgb[c](x, y)) ? weights[c] * rgb[c](x, y) : 0.0f;
            y_plane[std::size_t(y) * std::size_t(width) + std::size_t(x)] = v;
        }
    });
    return y_plane;
}

/// Sec. 4.1 passes 1-2: W_N's noise estimate E (ratio estimator Eq. 29, 3x3 box), as the
/// bilateral's sigma = sigma_per_noise x E, capped.
std::vector<float> bilateral_sigma_px(const RatioLayers &layers, bool grey, const RatioSettings &s, int width,
                                      int height) {
    const std::size_t count = std::size_t(width) * std::size_t(height);
    std::vector<float> s_y, u_y;
    ConstPlaneView s_view = layers.shadowed_y, u_view = layers.unshadowed_y;
    if (!grey) {
        s_y = luminance(layers.shadowed);
        u_y = luminance(layers.unshadowed);
        s_view = plane_view(static_cast<const float *>(s_y.data()), width, height);
        u_view = plane_view(static_cast<const float *>(u_y.data()), width, height);
    }
    std::vector<float> w(count), e(count);
    weighted_shadow(s_view, u_view, plane_view(w.data(), width, height));
    ratio_noise_estimate(plane_view(static_cast<const float *>(w.data()), width, height), s.noise_radius_px,
                         s.seed, plane_view(e.data(), width, height));
    for (float &v : e) v = std::min(s.sigma_per_noise_px * v, s.max_sigma_px);
    return e;
}

/// AAF's frequency-derived per-pixel widths (AAF Eq. 13, Mehta et al. 2012) as gather guides.
GatherGuides aaf_guides(const MethodImages &images, const float *any_plane) {
    for (Role role : {Role::D1, Role::D2Min, Role::D2Max, Role::ObjectId, Role::PixelSize})
        if (!images.has(role))
            throw InputError(std::string("--denoiser aaf needs the '") + role.key + "' input (channels " +
                             images.channel_names(role) + "; aaf render --aovs ratio,shadow,all)");
    for (const std::string &name : light_attribute_names())
        if (!images.attributes().count(name))
            throw InputError("--denoiser aaf needs the key light's header attribute '" + name + "'");
    AafInputs in = aaf_geometry_inputs(images);
    in.visibility = plane_view(any_plane, images.width(), images.height());
    // AAF's consistency rule (AAF Sec. 5.2): the widths follow the samples taken when they are known.
    if (images.has(Role::SamplesPerPixel)) in.spp = images.input(Role::SamplesPerPixel);
    return aaf_gather_guides(in, read_light_attributes(images.attributes()), AafParams{});
}

/// The planes filtered by a denoiser that writes them (gaussian, aaf), then composed.
void compose_planes(const RatioComposition &composition, const std::vector<std::vector<float>> &denoised,
                    const std::array<PlaneView, 3> &rgb, bool accumulate, int width, int height) {
    parallel_for_rows(height, [&](int y) {
        std::vector<const float *> rows;
        for (const std::vector<float> &plane : denoised)
            rows.push_back(&plane[std::size_t(y) * std::size_t(width)]);
        composition.compose_row(y, 0, width, rows.data(), rgb, accumulate);
    });
}

/// How the ratio estimator's beauty is made.
enum class RatioBeauty {
    Estimate,   ///< the estimate alone (Composition::Paper, or no input beauty)
    Corrected,  ///< the input beauty less S_N plus the estimate: the tracer's beauty holds S_N
    Kept,       ///< the input beauty as it was: it does not hold S_N
};

RatioBeauty ratio_beauty(const std::map<std::string, AttributeValue> &attributes,
                         const std::function<bool(Role)> &has, Composition composition) {
    if (composition == Composition::Paper || !has(Role::Beauty)) return RatioBeauty::Estimate;
    return beauty_holds_exactly(attributes, beauty_holds::kRatio) ? RatioBeauty::Corrected
                                                                  : RatioBeauty::Kept;
}

/// R,G,B from the estimate `direct`: the beauty's S_N replaced by it, so that
/// whatever else the renderer wrote passes through.
void write_beauty(const MethodImages &images, const std::array<PlaneView, 3> &direct) {
    const auto has = [&](Role role) { return images.has(role); };
    const RatioBeauty how = ratio_beauty(images.attributes(), has, images.composition());
    parallel_for_rows(images.height(), [&](int y) {
        for (std::size_t c = 0; c < 3; ++c) {
            const PlaneView beauty = images.output(Role::Beauty, c);
            const ConstPlaneView estimate = direct[c];
            if (how == RatioBeauty::Estimate) {
                for (int x = 0; x < images.width(); ++x) beauty(x, y) = estimate(x, y);
                continue;
            }
            const ConstPlaneView in = images.input(Role::Beauty, c);
            if (how == RatioBeauty::Kept) {
                for (int x = 0; x < images.width(); ++x) beauty(x, y) = in(x, y);
                continue;
            }
            const ConstPlaneView shadowed = images.input(roles::RatioShadowed, c);
            for (int x = 0; x < images.width(); ++x)
                beauty(x, y) = (in(x, y) - shadowed(x, y)) + estimate(x, y);
        }
    });
}

class RatioMethod final : public Method {
  public:
    RatioMethod() {
        info_.name = "ratio";
        info_.title = "ratio estimator";
        info_.summary =
            "Ratio estimator: analytic U times denoised S_N over denoised U_N (Heitz et al. 2018)";
        info_.reference =
            "Heitz, Hill, McGuire: Combining Analytic Direct Illumination and Stochastic Shadows, 2018";
        info_.roles.declared = ratio_roles();
        info_.roles.required = {roles::RatioAnalytic, roles::RatioShadowed, roles::RatioUnshadowed,
                                Role::Position, Role::Normal};
        info_.roles.optional = {roles::RatioShadowedLuminance,
                                roles::RatioUnshadowedLuminance,
                                Role::PixelSize,
                                Role::Motion,
                                Role::D1,
                                Role::D2Min,
                                Role::D2Max,
                                Role::ObjectId,
                                Role::SamplesPerPixel,
                                Role::Beauty};
        info_.roles.outputs = {roles::RatioDirect, Role::Beauty};
        info_.parameters = ratio_parameters().infos();
        info_.uses_history = true;
    }

    const MethodInfo &info() const override { return info_; }

    void check_parameters(const ParameterSet &parameters) const override { settings_from(parameters); }

    std::vector<Role> roles_needed(const ParameterSet &parameters) const override {
        const RatioSettings s = settings_from(parameters);
        std::vector<Role> roles = info_.roles.required;
        if (s.grey)
            roles.insert(roles.end(), {roles::RatioShadowedLuminance, roles::RatioUnshadowedLuminance});
        if (s.denoiser == "aaf")  // aaf_guides()
            roles.insert(roles.end(), {Role::D1, Role::D2Min, Role::D2Max, Role::ObjectId, Role::PixelSize});
        if (s.temporal) roles.push_back(Role::Motion);  // accumulate_history()
        return roles;
    }

    bool reads_history(const ParameterSet &parameters) const override {
        return ratio_parameters().read(parameters).temporal;
    }

    void run(const MethodImages &images, const ParameterSet &parameters, Progress &progress) const override {
        const RatioSettings s = settings_from(parameters);
        const int width = images.width(), height = images.height();
        const std::array<PlaneView, 3> rgb = {images.output(roles::RatioDirect, 0),
                                              images.output(roles::RatioDirect, 1),
                                              images.output(roles::RatioDirect, 2)};
        const std::vector<float> scale = scene_scale_m(images);
        RatioBilateralGuides guides;
        for (std::size_t c = 0; c < 3; ++c) {
            guides.position[c] = images.input(Role::Position, c);
            guides.normal[c] = images.input(Role::Normal, c);
        }
        guides.scale_m = plane_view(scale.data(), width, height);
        RatioBilateralSettings bilateral;
        bilateral.plane_sigma = s.plane_sigma;

        // Per light, then summed (Sec. 3.5 per light; several lights add).
        const int lights = s.summed ? 0 : images.light_count();
        std::vector<int> passes;
        for (int light = 0; light < lights; ++light) passes.push_back(light);
        if (passes.empty()) passes.push_back(-1);
        GatherGuides frequency_guides;
        for (std::size_t pass = 0; pass < passes.size(); ++pass) {
            const RatioLayers layers = layers_of(images, passes[pass], s.grey);
            const RatioComposition composition(layers, s.estimator, s.grey);
            const std::vector<FramePlane<float>> sources = composition.sources();
            const bool accumulate = pass > 0;
            if (s.denoiser == "bilateral") {
                const std::vector<float> sigma = bilateral_sigma_px(layers, s.grey, s, width, height);
                std::vector<ConstPlaneView> views;
                for (const FramePlane<float> &plane : sources)
                    views.push_back(plane_view(plane.data(), width, height));
                ratio_bilateral_compose(guides, plane_view(sigma.data(), width, height), bilateral, views,
                                        composition, rgb, accumulate);
            } else {
                std::vector<std::vector<float>> denoised(sources.size(),
                                                         std::vector<float>(sources.front().size()));
                if (s.denoiser == "gaussian") {
                    for (std::size_t k = 0; k < sources.size(); ++k)
                        fixed_gaussian_filter(plane_view(sources[k].data(), width, height),
                                              s.gaussian_sigma_px,
                                              plane_view(denoised[k].data(), width, height));
                } else {
                    if (pass == 0) frequency_guides = aaf_guides(images, sources.front().data());
                    std::vector<ConstPlaneView> in;
                    std::vector<PlaneView> out;
                    for (std::size_t k = 0; k < sources.size(); ++k) {
                        in.push_back(plane_view(sources[k].data(), width, height));
                        out.push_back(plane_view(denoised[k].data(), width, height));
                    }
                    gather(frequency_guides, aaf_gather_settings(AafParams{}), in, out);
                }
                compose_planes(composition, denoised, rgb, accumulate, width, height);
            }
            progress.report(0.9 * double(pass + 1) / double(passes.size()));
        }
        if (s.temporal) accumulate_history(images, s, scale, rgb);
        write_beauty(images, rgb);
    }

    std::string composition_note(const std::map<std::string, AttributeValue> &attributes,
                                 const std::function<bool(Role)> &has,
                                 Composition composition) const override {
        if (ratio_beauty(attributes, has, composition) != RatioBeauty::Kept) return {};
        return "R,G,B left as rendered: the beauty does not hold ratio.S (no " + std::string(attr::kBeauty) +
               " = " + beauty_holds::kRatio +
               "), so its direct light cannot be replaced; the estimate is in " +
               "ratio.direct.R/G/B, or --compose paper writes it to R,G,B";
    }

  private:
    /// Sec. 4.1 pass 5 on a sequence; the first frame has no history.
    static void accumulate_history(const MethodImages &images, const RatioSettings &s,
                                   const std::vector<float> &scale, const std::array<PlaneView, 3> &rgb) {
        if (!images.has(Role::Motion))
            throw InputError("--temporal needs the 'motion' input (channels " +
                             images.channel_names(Role::Motion) + ")");
        for (Role role : {roles::RatioDirect, Role::Position, Role::Normal})
            if (!images.has_history(role)) return;
        const int width = images.width(), height = images.height();
        TemporalFrame current, previous;
        for (std::size_t c = 0; c < 3; ++c) {
            current.colour[c] = rgb[c];
            current.position[c] = images.input(Role::Position, c);
            current.normal[c] = images.input(Role::Normal, c);
            previous.colour[c] = images.history(roles::RatioDirect, c);
            previous.position[c] = images.history(Role::Position, c);
            previous.normal[c] = images.history(Role::Normal, c);
        }
        current.scale_m = previous.scale_m = plane_view(scale.data(), width, height);
        TemporalSettings temporal;
        temporal.alpha = s.temporal_alpha;
        temporal_accumulate(current, {images.input(Role::Motion, 0), images.input(Role::Motion, 1)}, previous,
                            temporal, rgb);
    }

    MethodInfo info_;
};

}  // namespace

std::unique_ptr<Method> make_ratio_method() {
    return std::make_unique<RatioMethod>();
}

std::vector<std::string> ratio_parameter_defaults_read_back_differently() {
    return ratio_parameters().defaults_read_back_differently();
}

}  // namespace aaf
