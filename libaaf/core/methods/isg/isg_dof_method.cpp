// ISG depth of field (Robison and Shirley 2009, Sec. 3.3): a parameter search
// over the circles of confusion around a pixel sets the radius of a gather
// of the in-focus image, with depth-ordered range functions after Riguer et
// al. softened by a smoothstep.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/core/util/parallel.h"
#include "isg_common.h"

namespace aaf {

namespace {

using namespace isg;

constexpr float kInf = std::numeric_limits<float>::infinity();

/// How far `z` lies behind `z0`, relative to z0; the background is at +inf.
float relative_depth_behind(float z, float z0) {
    if (std::isinf(z0)) return std::isinf(z) ? 0.0f : -kInf;
    if (std::isinf(z)) return kInf;
    return (z - z0) / z0;
}

struct IsgDofSettings : CommonSettings {
    float transition = 0.05f;  ///< smoothstep width of ISG Eq. 16-17's depth test, relative to the depth
    float aperture_m = 0;      ///< lens aperture radius; 0 = the header's
    float focus_m = 0;         ///< depth in focus; 0 = the header's
};

const ParameterDeclarations<IsgDofSettings> &isg_dof_parameters() {
    using P = IsgDofSettings;
    static const auto declarations = std::move(
        common_parameters<P>("isg-dof")
            .real("transition", &P::transition, "",
                  "Width of the smoothstep that softens ISG Eq. 16-17's depth test, relative to the pixel's "
                  "depth (0 = the hard test)",
                  0, 1e3)
            .real("aperture", &P::aperture_m, "metres",
                  "Lens aperture radius; 0 = the header's aaf:camera:aperture_radius_m", 0, 1e3)
            .real("focus", &P::focus_m, "metres",
                  "Depth in focus z_f; 0 = the header's aaf:camera:focus_distance_m", 0, 1e9));
    return declarations;
}

class IsgDofMethod final : public Method {
  public:
    IsgDofMethod() {
        info_.name = "isg-dof";
        info_.title = "ISG depth of field";
        info_.summary =
            "Image Space Gathering depth of field from a pinhole image and depth (Robison, Shirley 2009)";
        info_.reference = "Robison, Shirley: Image Space Gathering, HPG 2009, Sec. 3.3";
        info_.roles.declared = isg_dof_roles();
        info_.roles.required = {roles::PinholeBeauty, Role::Depth};
        // Defocus touches the whole image: the defocused pinhole image is the beauty.
        info_.roles.outputs = {roles::Defocused, Role::Beauty};
        info_.roles.filtered = {{roles::PinholeBeauty, roles::Defocused}};
        info_.parameters = isg_dof_parameters().infos();
        info_.required_attributes = {attr::kCameraFocalPx};
    }

    const MethodInfo &info() const override { return info_; }

    void run(const MethodImages &images, const ParameterSet &parameters, Progress &progress) const override {
        const int width = images.width(), height = images.height();
        const IsgDofSettings settings = isg_dof_parameters().read(parameters);
        const CommonSettings &common = settings;
        const auto &attributes = images.attributes();
        const float focal_px = focal_px_attribute(attributes, height);
        float aperture_m = settings.aperture_m;
        if (!(aperture_m > 0)) aperture_m = non_negative_attribute(attributes, attr::kApertureRadius);
        float focus_m = settings.focus_m;
        if (!(focus_m > 0) && aperture_m > 0)
            focus_m = positive_attribute(attributes, attr::kFocusDistance, std::numeric_limits<float>::max());
        const float transition = settings.transition;
        // ISG Eq. 15's c_inf: the aperture seen from the plane in focus, in pixels.
        const float coc_inf_px = aperture_m > 0 && focus_m > 0 ? aperture_m / focus_m * focal_px : 0.0f;
        const std::vector<Tap> search = tap_set(common.search_samples, TapShape::Disk, common.pattern);
        const std::vector<Tap> gather = tap_set(common.gather_samples, TapShape::Disk, common.pattern);

        const Vec3Planes sharp = vec3_input(images, roles::PinholeBeauty);
        const ConstPlaneView depth_m = images.input(Role::Depth);
        const PlaneView out[3] = {images.output(roles::Defocused, 0), images.output(roles::Defocused, 1),
                                  images.output(roles::Defocused, 2)};
        // Depth 0 is the background, at infinity; a non-finite depth is unknown (NaN).
        auto depth = [&](int x, int y) {
            const float z = depth_m(x, y);
            return z == 0 ? kInf : std::isfinite(z) && z > 0 ? z : std::nanf("");
        };
        auto coc = [&](float z) { return circle_of_confusion_px(z, focus_m, coc_inf_px); };  // ISG Eq. 15

        parallel_for_rows(height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                for (int c = 0; c < 3; ++c) out[c](x, y) = sharp.c[c](x, y);
                const float z0 = depth(x, y);
                if (!(coc_inf_px > 0) || std::isnan(z0)) continue;
                const float c0 = coc(z0);
                // Parameter search within c_inf: the mean circle of confusion,
                // weighted by ISG Eq. 16: a tap behind the pixel with a larger
                // circle (a blurred background behind an in-focus object) counts
                // with its own radius instead of c_inf; the smoothstep fades the
                // test in with depth, so a tap on the pixel's own surface counts fully.
                const float search_px = clamp_radius(coc_inf_px, common.max_radius_px);
                double weight_sum = 0, coc_sum = 0;
                for (const Tap &tap : search) {
                    int sx, sy;
                    if (!tap_pixel(x, y, tap, search_px, width, height, sx, sy)) continue;
                    const float zi = depth(sx, sy);
                    if (std::isnan(zi)) continue;
                    const float ci = coc(zi);
                    const float behind =
                        ci > c0 ? smoothstep(transition, relative_depth_behind(zi, z0)) : 0.0f;
                    const float w = coc_inf_px + behind * (ci - coc_inf_px);  // ISG Eq. 16, smoothed
                    weight_sum += w;
                    coc_sum += double(w) * ci;
                }
                if (!(weight_sum > 0)) continue;
                const float gather_px = clamp_radius(float(coc_sum / weight_sum), common.max_radius_px);
                // Gather: ISG Eq. 17 keeps a sharper foreground tap from bleeding
                // over a blurred pixel behind it (weight its own small radius).
                auto tap_weight = [&](int sx, int sy, const Tap &) -> std::optional<float> {
                    const float zi = depth(sx, sy);
                    if (std::isnan(zi)) return std::nullopt;
                    const float ci = coc(zi);
                    const float in_front =
                        ci < c0 ? smoothstep(transition, -relative_depth_behind(zi, z0)) : 0.0f;
                    return coc_inf_px + in_front * (ci - coc_inf_px);  // ISG Eq. 17, smoothed
                };
                Vec3 mean;
                if (gather_colour(sharp, gather, x, y, gather_px, width, height, tap_weight, mean))
                    for (int c = 0; c < 3; ++c) out[c](x, y) = mean[c];
            }
        });
        for (int c = 0; c < 3; ++c) {
            const PlaneView beauty = images.output(Role::Beauty, std::size_t(c));
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) beauty(x, y) = out[c](x, y);
        }
        progress.report(0.95);
    }

  private:
    MethodInfo info_;
};

}  // namespace

std::unique_ptr<Method> make_isg_dof_method() {
    return std::make_unique<IsgDofMethod>();
}

std::vector<std::string> isg_dof_parameter_defaults_read_back_differently() {
    return isg_dof_parameters().defaults_read_back_differently();
}

}  // namespace aaf
