// ISG soft shadows (Robison and Shirley 2009, Sec. 3.1): a parameter search
// over the image-space hard shadow's occluder distances sets, per pixel, the
// radius of a cross-bilateral gather of the hard visibility.
#include <algorithm>
#include <cmath>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/kernels/shadow_composition.h"
#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/core/util/parallel.h"
#include "isg_common.h"

namespace aaf {

namespace {

using namespace isg;

struct IsgShadowSettings : CommonSettings {
    TapShape light_shape = TapShape::Rectangle;  ///< the taps', the virtual light's (ISG Sec. 3.1)
    float light_scale = 1;                       ///< L of ISG Eq. 5 and 8 over the light's half-extent
};

const ParameterDeclarations<IsgShadowSettings> &isg_shadow_parameters() {
    using P = IsgShadowSettings;
    static const auto declarations = std::move(
        common_parameters<P>("isg-shadow")
            .choice("light_shape", &P::light_shape,
                    {{"rectangle", TapShape::Rectangle}, {"disk", TapShape::Disk}},
                    "Shape of the taps, the virtual light's shape (ISG Sec. 3.1): the light's rectangle (its "
                    "width:height, along the image axes) or a disc")
            .real("light_scale", &P::light_scale, "",
                  "L of ISG Eq. 5 and 8 as a multiple of the light's half-extent (its larger half-side)", 0,
                  1e6,
                  /*min_open=*/true));
    return declarations;
}

class IsgShadowMethod final : public Method {
  public:
    IsgShadowMethod() {
        info_.name = "isg-shadow";
        info_.title = "ISG shadows";
        info_.summary =
            "Image Space Gathering soft shadows from one shadow ray per pixel (Robison, Shirley 2009)";
        info_.reference = "Robison, Shirley: Image Space Gathering, HPG 2009, Sec. 3.1";
        info_.roles.declared = isg_shadow_roles();
        info_.roles.required = {roles::HardVisibility, roles::OccluderDistance, Role::Position, Role::Depth,
                                Role::Unshadowed};
        info_.roles.optional = shadow_composition_roles();
        info_.roles.rendered = {Role::Visibility};  // the beauty's own, replaced by the filtered one
        info_.roles.outputs = {Role::FilteredVisibility, Role::Beauty};
        info_.roles.filtered = {{roles::HardVisibility, Role::FilteredVisibility}};
        info_.parameters = isg_shadow_parameters().infos();
        info_.required_attributes = light_attribute_names();
        info_.required_attributes.push_back(attr::kCameraFocalPx);
    }

    const MethodInfo &info() const override { return info_; }

    void run(const MethodImages &images, const ParameterSet &parameters, Progress &progress) const override {
        const int width = images.width(), height = images.height();
        const IsgShadowSettings settings = isg_shadow_parameters().read(parameters);
        const CommonSettings &common = settings;
        const LightPlane light = read_light_attributes(images.attributes());
        const float focal_px = focal_px_attribute(images.attributes(), height);
        const float light_size_m = settings.light_scale * 0.5f * std::max(light.width_m, light.height_m);
        const TapShape shape = settings.light_shape;
        const std::vector<Tap> search =
            tap_set(common.search_samples, shape, common.pattern, light.width_m, light.height_m);
        const std::vector<Tap> gather =
            tap_set(common.gather_samples, shape, common.pattern, light.width_m, light.height_m);

        const ConstPlaneView hard = images.input(roles::HardVisibility);
        const ConstPlaneView occluder_m = images.input(roles::OccluderDistance);
        const ConstPlaneView depth_m = images.input(Role::Depth);
        const Vec3Planes position = vec3_input(images, Role::Position);
        const PlaneView out = images.output(Role::FilteredVisibility);
        // ISG Sec. 5: sigma is relative to the scene's size, so l is measured in scene sizes.
        const float inv_scene_size = 1.0f / scene_size_m(position, width, height, common.scene_size_m);
        const float inv_sigma = 1.0f / common.sigma;
        auto range = [&](Vec3 p, Vec3 p0) {
            const float l = length(p - p0) * inv_scene_size;  // ISG Eq. 7
            return std::exp(-l * l * inv_sigma);              // ISG Eq. 6 without the in-shadow factor
        };

        parallel_for_rows(height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                out(x, y) = hard(x, y);
                const float z_eye = depth_m(x, y);
                const Vec3 p0 = position(x, y);
                if (!(z_eye > 0) || !std::isfinite(z_eye) || !all_finite(p0)) continue;
                // Parameter search (ISG Eq. 4-7): the mean occluder distance of the
                // in-shadow taps within the light's projected size.
                const float search_px = clamp_radius(screen_radius_px(light_size_m, z_eye, focal_px),
                                                     common.max_radius_px);  // ISG Eq. 5
                double weight_sum = 0, distance_sum = 0;
                for (const Tap &tap : search) {
                    int sx, sy;
                    if (!tap_pixel(x, y, tap, search_px, width, height, sx, sy)) continue;
                    const float d = occluder_m(sx, sy);
                    if (!(hard(sx, sy) < 0.5f) || !(d >= 0) || !std::isfinite(d))
                        continue;  // inShadow of ISG Eq. 6
                    const float w = range(position(sx, sy), p0);
                    if (!std::isfinite(w)) continue;
                    weight_sum += w;
                    distance_sum += double(w) * d;
                }
                if (!(weight_sum > 0)) continue;  // no occluder within reach: the hard value stands
                const float d_m = float(distance_sum / weight_sum);
                const float light_distance_m = length(light.center - p0);
                const float penumbra_m = penumbra_radius_m(light_size_m, d_m, light_distance_m);  // ISG Eq. 8
                const float gather_px = clamp_radius(screen_radius_px(penumbra_m, z_eye, focal_px),
                                                     common.max_radius_px);  // ISG Eq. 9
                // Gather (ISG Eq. 4): the hard visibility, constant spatial weight, range of ISG Eq. 6-7.
                double gather_weight = 0, visibility_sum = 0;
                for (const Tap &tap : gather) {
                    int sx, sy;
                    if (!tap_pixel(x, y, tap, gather_px, width, height, sx, sy)) continue;
                    const float v = hard(sx, sy);
                    const float w = range(position(sx, sy), p0);
                    if (!std::isfinite(v) || !std::isfinite(w)) continue;
                    gather_weight += w;
                    visibility_sum += double(w) * v;
                }
                if (gather_weight > 0) out(x, y) = float(visibility_sum / gather_weight);
            }
        });
        progress.report(0.9);
        compose_shadowed_beauty(images, out);  // AAF Eq. 1, or the beauty corrected
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

std::unique_ptr<Method> make_isg_shadow_method() {
    return std::make_unique<IsgShadowMethod>();
}

std::vector<std::string> isg_shadow_parameter_defaults_read_back_differently() {
    return isg_shadow_parameters().defaults_read_back_differently();
}

}  // namespace aaf
