// ISG soft shadows (Robison and Shirley 2009, Sec. 3.1): a parameter search
// over the image-space hard shadow's occluder distances sets, per pixel, the
// radius of a cross-bilateral gather of the hard visibility.
#include <algorithm>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/kernels/shadow_composition.h"
#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/core/util/parallel.h"
#include "isg_common.h"
#include "isg_rows.h"
#include "isg_shadow.h"

namespace aaf {

namespace {

using namespace isg;

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
        const IsgShadowSettings settings = isg_shadow_parameters().read(parameters);
        const LightPlane light = read_light_attributes(images.attributes());
        const float focal_px = focal_px_attribute(images.attributes(), images.height());
        const ShadowInputs in = {images.input(roles::HardVisibility), images.input(roles::OccluderDistance),
                                 images.input(Role::Depth), vec3_input(images, Role::Position)};
        const PlaneView out = images.output(Role::FilteredVisibility);
        isg_shadow_visibility(in, settings, light, focal_px, out);
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

isg::IsgShadowSettings isg::isg_shadow_settings(const ParameterSet &parameters) {
    return isg_shadow_parameters().read(parameters);
}

void isg::isg_shadow_visibility(const ShadowInputs &in, const IsgShadowSettings &settings,
                                const LightPlane &light, float focal_px, PlaneView out) {
    const int width = in.hard.width, height = in.hard.height;
    const float light_size_m = settings.light_scale * 0.5f * std::max(light.width_m, light.height_m);
    const TapShape shape = settings.light_shape;
    const TapArrays search_taps(
        tap_set(settings.search_samples, shape, settings.pattern, light.width_m, light.height_m));
    const TapArrays gather_taps(
        tap_set(settings.gather_samples, shape, settings.pattern, light.width_m, light.height_m));
    const SweepPlanes planes(
        {in.hard, in.occluder_m, in.depth_m, in.position.c[0], in.position.c[1], in.position.c[2]});
    ShadowSweep sweep;
    sweep.layout = planes.layout();
    sweep.hard = planes[0];
    sweep.occluder_m = planes[1];
    sweep.depth_m = planes[2];
    for (int c = 0; c < 3; ++c) sweep.position[c] = planes[std::size_t(3 + c)];
    sweep.search = &search_taps;
    sweep.gather = &gather_taps;
    // ISG Sec. 5: sigma is relative to the scene's size, so l is measured in scene sizes.
    sweep.range = {1.0f / scene_size_m(in.position, width, height, settings.scene_size_m),
                   1.0f / settings.sigma, settings.max_radius_px};
    sweep.light_size_m = light_size_m;
    sweep.focal_px = focal_px;
    sweep.light_center = light.center;
    sweep.out = out;
    sweep.pass_over_uniform = settings.pass_over_uniform;
    ShadowScratch scratch;
    prepare_shadow_sweep(sweep, scratch);
    parallel_for_rows(height, [&](int y) { shadow_row(sweep, y); });
}

std::unique_ptr<Method> make_isg_shadow_method() {
    return std::make_unique<IsgShadowMethod>();
}

std::vector<std::string> isg_shadow_parameter_defaults_read_back_differently() {
    return isg_shadow_parameters().defaults_read_back_differently();
}

}  // namespace aaf
