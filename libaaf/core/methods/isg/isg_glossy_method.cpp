// ISG glossy reflections (Robison and Shirley 2009, Sec. 3.2): a parameter
// search over the reflection map's distances sets, per pixel, the support of
// a cross-bilateral gather of the mirror reflection over the glossy cone.
#include <algorithm>
#include <cmath>
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

struct IsgGlossySettings : CommonSettings {
    float a = 1, b = 1;            ///< weights of the world distance and the normals' difference (ISG Eq. 10)
    bool gaussian_weight = false;  ///< the gather's spatial weight: a Gaussian, else constant (ISG Sec. 3.2)
};

const ParameterDeclarations<IsgGlossySettings> &isg_glossy_parameters() {
    using P = IsgGlossySettings;
    static const auto declarations = std::move(
        common_parameters<P>("isg-glossy")
            .real("a", &P::a, "", "Weight of the world distance in ISG Eq. 10", 0, 1e6)
            .real("b", &P::b, "", "Weight of the normals' difference 1 - N.N0 in ISG Eq. 10", 0, 1e6)
            .choice(
                "spatial_weight", &P::gaussian_weight, {{"constant", false}, {"gaussian", true}},
                "The gather's spatial weight, the BRDF's shape in the cone (ISG Sec. 3.2): constant, or a "
                "Gaussian of standard deviation half the radius"));
    return declarations;
}

class IsgGlossyMethod final : public Method {
  public:
    IsgGlossyMethod() {
        info_.name = "isg-glossy";
        info_.title = "ISG glossy";
        info_.summary =
            "Image Space Gathering glossy reflections from one mirror ray per pixel (Robison, Shirley 2009)";
        info_.reference = "Robison, Shirley: Image Space Gathering, HPG 2009, Sec. 3.2";
        info_.roles.declared = isg_glossy_roles();
        info_.roles.required = {roles::Reflection, roles::ReflectionDistance, roles::ThetaMax, Role::Position,
                                Role::Normal};
        info_.roles.outputs = {roles::GlossyReflection};
        // The tracer's beauty holds no glossy reflection (SCENE_FORMAT.md):
        // the estimate is compared with the cone-sampled reference.
        info_.compared = {roles::GlossyReflection, roles::GlossyReference};
        info_.roles.filtered = {{roles::Reflection, roles::GlossyReflection}};
        info_.parameters = isg_glossy_parameters().infos();
        info_.required_attributes = {attr::kCameraEye, attr::kCameraFocalPx};
    }

    const MethodInfo &info() const override { return info_; }

    void run(const MethodImages &images, const ParameterSet &parameters, Progress &progress) const override {
        const int width = images.width(), height = images.height();
        const IsgGlossySettings settings = isg_glossy_parameters().read(parameters);
        const CommonSettings &common = settings;
        const Vec3 eye = vec3_attribute(images.attributes(), attr::kCameraEye);
        const float focal_px = focal_px_attribute(images.attributes(), height);
        // ISG Sec. 3.2 projects angles by the field of view: pixels per radian.
        const float fov_y_rad = 2 * std::atan(0.5f * float(height) / focal_px);
        const float px_per_rad = float(height) / fov_y_rad;
        const std::vector<Tap> search = tap_set(common.search_samples, TapShape::Disk, common.pattern);
        const std::vector<Tap> gather = tap_set(common.gather_samples, TapShape::Disk, common.pattern);

        const Vec3Planes position = vec3_input(images, Role::Position);
        const Vec3Planes reflection = vec3_input(images, roles::Reflection);
        const Vec3Planes normal = vec3_input(images, Role::Normal);
        const SweepPlanes planes({reflection.c[0], reflection.c[1], reflection.c[2], position.c[0],
                                  position.c[1], position.c[2], normal.c[0], normal.c[1], normal.c[2],
                                  images.input(roles::ReflectionDistance), images.input(roles::ThetaMax)});
        const TapArrays search_taps(search), gather_taps(gather);
        // The gather's spatial weight per tap; Gaussian: standard deviation
        // half the radius, exp(-r^2 / (2 (R/2)^2)).
        std::vector<float> spatial;
        for (const Tap &tap : gather)
            spatial.push_back(settings.gaussian_weight ? std::exp(-2 * (tap.x * tap.x + tap.y * tap.y))
                                                       : 1.0f);
        GlossySweep sweep;
        sweep.layout = planes.layout();
        for (int c = 0; c < 3; ++c) {
            sweep.reflection[c] = planes[std::size_t(c)];
            sweep.position[c] = planes[std::size_t(3 + c)];
            sweep.normal[c] = planes[std::size_t(6 + c)];
            sweep.out[c] = images.output(roles::GlossyReflection, std::size_t(c));
        }
        sweep.reflected_m = planes[9];
        sweep.theta_max = planes[10];
        sweep.search = &search_taps;
        sweep.gather = &gather_taps;
        sweep.gather_spatial = spatial.data();
        sweep.range = {1.0f / scene_size_m(position, width, height, common.scene_size_m), 1.0f / common.sigma,
                       common.max_radius_px};
        sweep.a = settings.a;
        sweep.b = settings.b;
        sweep.px_per_rad = px_per_rad;
        sweep.eye = eye;
        // Per pixel: the mean reflected distance within theta_max's projection
        // (the parameter search, range of ISG Eq. 10-12), the gather angle of
        // ISG Eq. 13-14, then the gather (ISG Eq. 4) of the mirror reflection.
        parallel_for_rows(height, [&](int y) { glossy_row(sweep, y); });
        progress.report(0.95);
    }

  private:
    MethodInfo info_;
};

}  // namespace

std::unique_ptr<Method> make_isg_glossy_method() {
    return std::make_unique<IsgGlossyMethod>();
}

std::vector<std::string> isg_glossy_parameter_defaults_read_back_differently() {
    return isg_glossy_parameters().defaults_read_back_differently();
}

}  // namespace aaf
