// ISG glossy reflections (Robison and Shirley 2009, Sec. 3.2): a parameter
// search over the reflection map's distances sets, per pixel, the support of
// a cross-bilateral gather of the mirror reflection over the glossy cone.
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
        const float a = settings.a, b = settings.b;
        const bool gaussian = settings.gaussian_weight;
        const std::vector<Tap> search = tap_set(common.search_samples, TapShape::Disk, common.pattern);
        const std::vector<Tap> gather = tap_set(common.gather_samples, TapShape::Disk, common.pattern);

        const Vec3Planes reflection = vec3_input(images, roles::Reflection);
        const ConstPlaneView reflected_m = images.input(roles::ReflectionDistance);
        const ConstPlaneView theta_max = images.input(roles::ThetaMax);
        const Vec3Planes position = vec3_input(images, Role::Position);
        const Vec3Planes normal = vec3_input(images, Role::Normal);
        const PlaneView out[3] = {images.output(roles::GlossyReflection, 0),
                                  images.output(roles::GlossyReflection, 1),
                                  images.output(roles::GlossyReflection, 2)};
        const float inv_scene_size = 1.0f / scene_size_m(position, width, height, common.scene_size_m);
        const float inv_sigma = 1.0f / common.sigma;
        auto range = [&](int sx, int sy, Vec3 p0, Vec3 n0) {
            const float l = length(position(sx, sy) - p0) * inv_scene_size;  // ISG Eq. 11
            const float n = 1 - dot(normal(sx, sy), n0);                     // ISG Eq. 12
            return std::exp(-(a * l * l + b * n * n) * inv_sigma);           // ISG Eq. 10
        };

        parallel_for_rows(height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                for (int c = 0; c < 3; ++c) out[c](x, y) = reflection.c[c](x, y);
                const float theta = theta_max(x, y);
                const Vec3 p0 = position(x, y), n0 = normal(x, y);
                if (!(theta > 0) || !std::isfinite(theta) || !all_finite(p0) || !all_finite(n0)) continue;
                // Parameter search: the mean reflected distance within theta_max's projection.
                const float search_px = clamp_radius(theta * px_per_rad, common.max_radius_px);
                double weight_sum = 0, distance_sum = 0;
                for (const Tap &tap : search) {
                    int sx, sy;
                    if (!tap_pixel(x, y, tap, search_px, width, height, sx, sy)) continue;
                    const float e_m = reflected_m(sx, sy);
                    if (!(e_m > 0) || !std::isfinite(e_m))
                        continue;  // a ray that left the scene has no distance
                    const float w = range(sx, sy, p0, n0);
                    if (!std::isfinite(w)) continue;
                    weight_sum += w;
                    distance_sum += double(w) * e_m;
                }
                const float reflected_distance_m = weight_sum > 0 ? float(distance_sum / weight_sum)
                                                                  : std::numeric_limits<float>::infinity();
                const Vec3 to_eye = eye - p0;
                const float eye_distance_m = length(to_eye);
                const float alpha =
                    glossy_gather_angle(theta, eye_distance_m, reflected_distance_m);  // ISG Eq. 13
                const float cos_incident = std::fabs(dot(n0, to_eye)) / eye_distance_m;
                const float gather_px =
                    clamp_radius(alpha * px_per_rad * cos_incident, common.max_radius_px);  // ISG Eq. 14
                auto tap_weight = [&](int sx, int sy, const Tap &tap) -> std::optional<float> {
                    // Gaussian: standard deviation half the radius, exp(-r^2 / (2 (R/2)^2)).
                    const float spatial = gaussian ? std::exp(-2 * (tap.x * tap.x + tap.y * tap.y)) : 1.0f;
                    const float w = spatial * range(sx, sy, p0, n0);
                    if (!std::isfinite(w)) return std::nullopt;
                    return w;
                };
                Vec3 mean;
                if (gather_colour(reflection, gather, x, y, gather_px, width, height, tap_weight, mean))
                    for (int c = 0; c < 3; ++c) out[c](x, y) = mean[c];
            }
        });
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
