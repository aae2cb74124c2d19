// ISG depth of field (Robison and Shirley 2009, Sec. 3.3): a parameter search
// over the circles of confusion around a pixel sets the radius of a gather
// of the in-focus image, with depth-ordered range functions after Riguer et
// al. softened by a smoothstep.
#include <algorithm>
#include <limits>
#include <vector>

#include "../builtin_methods.h"
#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/parameter_defaults.h"
#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/core/util/parallel.h"
#include "isg_common.h"
#include "isg_rows.h"

namespace aaf {

namespace {

using namespace isg;

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
        const int height = images.height();
        const IsgDofSettings settings = isg_dof_parameters().read(parameters);
        const CommonSettings &common = settings;
        const auto &attributes = images.attributes();
        const float focal_px = focal_px_attribute(attributes, height);
        float aperture_m = settings.aperture_m;
        if (!(aperture_m > 0)) aperture_m = non_negative_attribute(attributes, attr::kApertureRadius);
        float focus_m = settings.focus_m;
        if (!(focus_m > 0) && aperture_m > 0)
            focus_m = positive_attribute(attributes, attr::kFocusDistance, std::numeric_limits<float>::max());
        // ISG Eq. 15's c_inf: the aperture seen from the plane in focus, in pixels.
        const float coc_inf_px = aperture_m > 0 && focus_m > 0 ? aperture_m / focus_m * focal_px : 0.0f;
        const std::vector<Tap> search = tap_set(common.search_samples, TapShape::Disk, common.pattern);
        const std::vector<Tap> gather = tap_set(common.gather_samples, TapShape::Disk, common.pattern);

        const Vec3Planes sharp = vec3_input(images, roles::PinholeBeauty);
        const SweepPlanes planes({sharp.c[0], sharp.c[1], sharp.c[2], images.input(Role::Depth)});
        const TapArrays search_taps(search), gather_taps(gather);
        DofSweep sweep;
        sweep.layout = planes.layout();
        for (int c = 0; c < 3; ++c) {
            sweep.sharp[c] = planes[std::size_t(c)];
            sweep.out[c] = images.output(roles::Defocused, std::size_t(c));
            sweep.beauty[c] = images.output(Role::Beauty, std::size_t(c));
        }
        sweep.depth_m = planes[3];
        sweep.search = &search_taps;
        sweep.gather = &gather_taps;
        sweep.max_radius_px = common.max_radius_px;
        sweep.focus_m = focus_m;
        sweep.coc_inf_px = coc_inf_px;
        sweep.transition = settings.transition;
        // Per pixel: the mean circle of confusion (ISG Eq. 15) within c_inf,
        // weighted after ISG Eq. 16: a tap behind the pixel with a larger circle
        // (a blurred background behind an in-focus object) counts with its own
        // radius instead of c_inf, the smoothstep fading the test in with
        // depth; then the gather (ISG Eq. 4) of the pinhole image, where ISG Eq. 17
        // keeps a sharper foreground tap from bleeding over a blurred pixel
        // behind it. Depth 0 is the background at infinity, a non-finite
        // depth unknown. The defocused image is also the beauty.
        parallel_for_rows(height, [&](int y) { dof_row(sweep, y); });
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
