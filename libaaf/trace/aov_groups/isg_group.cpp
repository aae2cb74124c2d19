#include <cmath>

#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"
#include "aov_groups.h"
#include "random.h"
#include "stratified_grid.h"

namespace aaf::trace {

namespace {

constexpr float kPi = 3.14159265358979323846f;
/// Distinguishes the glossy reference's random numbers from the light samples'.
constexpr std::uint64_t kGlossyStream = 0x9e6c63d0676a9a99ull;

/// A unit vector `cos_theta` off the unit axis `w`, at azimuth `phi`.
Vec3 around(Vec3 w, float cos_theta, float phi) {
    const Vec3 helper = std::fabs(w.x) > 0.9f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    const Vec3 u = normalize(cross(helper, w)), v = cross(w, u);
    const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
    return u * (sin_theta * std::cos(phi)) + v * (sin_theta * std::sin(phi)) + w * cos_theta;
}

/// ISG's inputs (Robison and Shirley 2009) as a ray tracer makes them, one
/// ray per pixel and effect: the image-space hard shadow (Sec. 3.1), the
/// mirror reflection map and theta_max (Sec. 3.2), the pinhole image whose
/// defocus Sec. 3.3 simulates; and the distribution-ray-traced glossy
/// reference (the soft-shadow reference is shadow.V, the defocus reference
/// a thin-lens beauty). Also the camera attributes the filters project with.
class IsgGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override {
        AovGroupInfo info = group_info("isg",
                                       "isg.V, isg.occluder_m, reflect.R/G/B, reflect.E, gloss.theta_max, "
                                       "glossy.R/G/B, pinhole.R/G/B",
                                       roles());
        return info;
    }
    std::vector<Role> roles() const override {
        return {roles::HardVisibility,     roles::OccluderDistance, roles::Reflection,
                roles::ReflectionDistance, roles::ThetaMax,         roles::GlossyReference,
                roles::PinholeBeauty};
    }

    void write(const RenderState &state, AovSet &aovs) const override {
        if (!state.renderer) throw Error("internal: the isg group needs the render's tracer");
        const Renderer &renderer = *state.renderer;
        const Camera &camera = state.scene.camera;
        const auto hard = add_role_channels(aovs, roles::HardVisibility);
        const auto occluder = add_role_channels(aovs, roles::OccluderDistance);
        const auto reflection = add_role_channels(aovs, roles::Reflection);
        const auto reflected = add_role_channels(aovs, roles::ReflectionDistance);
        const auto theta_max = add_role_channels(aovs, roles::ThetaMax);
        const auto glossy = add_role_channels(aovs, roles::GlossyReference);
        const auto pinhole = add_role_channels(aovs, roles::PinholeBeauty);
        aovs.attributes[attr::kCameraEye] = camera.eye;
        aovs.attributes[attr::kCameraFocalPx] = 0.5f * float(camera.height) / camera.tan_half_fov_y;
        aovs.attributes[attr::kFocusDistance] = camera.focus_distance_m;

        const StratifiedGrid strata(std::uint32_t(std::max(1, state.spp)));
        // Each pixel is written by one call and draws its own random numbers, so
        // the result does not depend on the schedule.
        parallel_for_rows(state.height, [&](int y) {
            for (int x = 0; x < state.width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(state.width) + std::size_t(x);
                const PrimaryHit &primary = state.primaries[i];
                hard[0](x, y) = 1.0f;
                if (!primary.found) continue;
                // The key light only (a pinhole's other lights are in otherlights.*).
                set3(pinhole, x, y, primary.unshadowed * state.stats[i].visibility());
                const Renderer::CentreShadow shadow = renderer.trace_centre_shadow(primary);
                hard[0](x, y) = shadow.visible ? 1.0f : 0.0f;
                occluder[0](x, y) = shadow.occluder_m;

                const Vec3 incoming = normalize(primary.position - camera.eye);
                const Vec3 mirror = incoming - primary.normal * (2 * dot(incoming, primary.normal));
                const Renderer::SecondaryHit seen = renderer.trace_secondary(primary, mirror);
                set3(reflection, x, y, seen.radiance);
                reflected[0](x, y) = seen.distance_m;

                const float theta = primary.mesh->material.theta_max_deg * kPi / 180;
                theta_max[0](x, y) = theta;
                if (!(theta > 0)) {
                    set3(glossy, x, y, seen.radiance);
                    continue;
                }
                // Uniform in solid angle within theta_max of the mirror direction;
                // rays below the surface are absorbed.
                PixelRng rng(state.seed ^ kGlossyStream, i, 0);
                const std::uint32_t key = rng.next_u32();
                const float one_minus_cos_max = 1 - std::cos(theta);
                Vec3 sum;
                for (std::uint32_t s = 0; s < strata.count(); ++s) {
                    float u1, u2;
                    rng.next_float2(u1, u2);
                    const UnitPoint u = strata.point(s, key, u1, u2);
                    const Vec3 direction = around(mirror, 1 - u.s * one_minus_cos_max, 2 * kPi * u.t);
                    if (dot(direction, primary.normal) <= 0) continue;
                    sum = sum + renderer.trace_secondary(primary, direction).radiance;
                }
                set3(glossy, x, y, sum / float(strata.count()));
            }
        });
    }
};

}  // namespace

std::unique_ptr<AovAccumulator> make_isg_group() {
    return std::make_unique<IsgGroup>();
}

}  // namespace aaf::trace
