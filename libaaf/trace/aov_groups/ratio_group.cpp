#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "../ratio_sampling.h"
#include "aaf/core/methods/ratio/ratio_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"
#include "aov_groups.h"

namespace aaf::trace {

namespace {

double luminance(Vec3 c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;  // Rec. 709, ratio estimator Sec. 3.4
}

/// Every pixel's ratio layers for every light, pixel-major: index
/// pixel * lights + light. Background pixels stay zero.
std::vector<RatioLayers> trace_all_ratio_layers(const RenderState &state) {
    if (!state.renderer) throw Error("internal: the ratio groups need the render's tracer");
    const std::size_t lights = state.scene.lights.size();
    std::vector<RatioLayers> layers(std::size_t(state.width) * std::size_t(state.height) * lights);
    const int samples = std::max(1, state.spp);
    // Each pixel draws its own random numbers: the result does not depend on the schedule.
    parallel_for_rows(state.height, [&](int y) {
        for (int x = 0; x < state.width; ++x) {
            const std::size_t pixel = std::size_t(y) * std::size_t(state.width) + std::size_t(x);
            const PrimaryHit &primary = state.primaries[pixel];
            if (!primary.found) continue;
            for (std::size_t l = 0; l < lights; ++l)
                layers[pixel * lights + l] = trace_ratio_layers(state.renderer->rays(), state.scene, primary,
                                                                l, samples, state.seed, pixel);
        }
    });
    return layers;
}

/// The layers of one render, traced at the group's first write and kept:
/// a progressive render writes its groups at every checkpoint, and the ratio
/// samples (all N of them, whatever the rounds done) need tracing only once.
class RatioLayerCache {
  public:
    const std::vector<RatioLayers> &get(const RenderState &state) const {
        if (!layers_) layers_ = trace_all_ratio_layers(state);
        return *layers_;
    }

  private:
    mutable std::optional<std::vector<RatioLayers>> layers_;
};

/// `name` with its leading "ratio." replaced by "ratio.L<light>.".
std::string per_light_name(const std::string &name, std::size_t light) {
    return "ratio.L" + std::to_string(light) + "." + name.substr(std::string("ratio.").size());
}

std::vector<PlaneView> add_channels(AovSet &aovs, const std::vector<std::string> &names) {
    std::vector<PlaneView> views;
    for (const std::string &name : names) views.push_back(aovs.add_channel(name));
    return views;
}

/// The contract's ratio layer (AOV_CONTRACT.md, ratio_u .. ratio_un_y):
/// U, S_N, U_N and the luminances, summed over the lights and per light,
/// from state.spp samples per light and pixel.
class RatioGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override {
        AovGroupInfo info = group_info(
            "ratio",
            "ratio.U.R/G/B, ratio.S.R/G/B, ratio.Un.R/G/B, ratio.S.Y, ratio.Un.Y, the same per light "
            "as ratio.L<i>.*, and aaf:ratio:lights; spp samples per light (MIS of light and GGX)",
            roles());
        return info;
    }
    std::vector<Role> roles() const override {
        return {roles::RatioAnalytic, roles::RatioShadowed, roles::RatioUnshadowed,
                roles::RatioShadowedLuminance, roles::RatioUnshadowedLuminance};
    }

    void write(const RenderState &state, AovSet &aovs) const override {
        const std::vector<RatioLayers> &layers = cache_.get(state);
        const std::size_t lights = state.scene.lights.size();
        const Role roles[] = {roles::RatioAnalytic, roles::RatioShadowed, roles::RatioUnshadowed,
                              roles::RatioShadowedLuminance, roles::RatioUnshadowedLuminance};
        // views[0] the sum, views[1 + l] light l; per role.
        std::vector<std::vector<std::vector<PlaneView>>> views(lights + 1);
        for (std::size_t target = 0; target <= lights; ++target)
            for (Role role : roles) {
                std::vector<std::string> names = role_info(role).channels;
                if (target > 0)
                    for (std::string &name : names) name = per_light_name(name, target - 1);
                views[target].push_back(add_channels(aovs, names));
            }
        aovs.attributes[attr::kRatioLights] = int(lights);
        // A pinhole's beauty is the direct light of every light: its estimate
        // from these samples, S_N (area lights with their BRDF, MIS), rather than
        // the key light's r(x) V(x), so that `aaf filter ratio` replaces exactly
        // it (attr::kBeauty). Through a lens the beauty keeps its defocus.
        const bool beauty_is_s = !state.scene.camera.is_thin_lens();
        std::vector<PlaneView> beauty, key_light;
        if (beauty_is_s) {
            for (const std::string &name : role_info(Role::Beauty).channels)
                beauty.push_back(aovs.channel(name));
            // The key light's part of that beauty, for the filters of its shadow alone
            // (shadow_composition.h).
            key_light = add_role_channels(aovs, Role::KeyLight);
            aovs.attributes[attr::kBeauty] = std::string(beauty_holds::kRatio);
        }
        state.for_each_pixel([&](int x, int y, const PrimaryHit &, const ShadowStats &) {
            const std::size_t pixel = std::size_t(y) * std::size_t(state.width) + std::size_t(x);
            double sum[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
            for (std::size_t l = 0; l < lights; ++l) {
                const RatioLayers &light = layers[pixel * lights + l];
                const Vec3 values[3] = {light.analytic, light.shadowed, light.unshadowed};
                for (int k = 0; k < 3; ++k) {
                    set3(views[1 + l][std::size_t(k)], x, y, values[k]);
                    for (int c = 0; c < 3; ++c) sum[k][c] += double(values[k][c]);
                }
                views[1 + l][3][0](x, y) = float(luminance(light.shadowed));
                views[1 + l][4][0](x, y) = float(luminance(light.unshadowed));
            }
            Vec3 totals[3];
            for (int k = 0; k < 3; ++k) {
                totals[k] = Vec3{float(sum[k][0]), float(sum[k][1]), float(sum[k][2])};
                set3(views[0][std::size_t(k)], x, y, totals[k]);
            }
            if (beauty_is_s) {
                set3(beauty, x, y, totals[1]);
                if (lights > 0) set3(key_light, x, y, layers[pixel * lights].shadowed);
            }
            views[0][3][0](x, y) = float(luminance(totals[1]));
            views[0][4][0](x, y) = float(luminance(totals[2]));
        });
    }

  private:
    RatioLayerCache cache_;
};

/// The two estimators the ratio estimator is compared with, from the same
/// samples as the ratio group: full-stochastic S_N (ratio estimator Eq. 10) and
/// control-variate U - U_N + S_N (ratio estimator Eq. 11, may be negative), summed over the lights.
class RatioEstimatorsGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override {
        AovGroupInfo info = group_info(
            "ratio_estimators",
            "ratio.sto.R/G/B (Eq. 10), ratio.cv.R/G/B (Eq. 11): the ratio group's samples", roles());
        return info;
    }
    std::vector<Role> roles() const override { return {}; }

    void write(const RenderState &state, AovSet &aovs) const override {
        const std::vector<RatioLayers> &layers = cache_.get(state);
        const std::size_t lights = state.scene.lights.size();
        const auto stochastic = add_channels(aovs, {"ratio.sto.R", "ratio.sto.G", "ratio.sto.B"});
        const auto control_variate = add_channels(aovs, {"ratio.cv.R", "ratio.cv.G", "ratio.cv.B"});
        state.for_each_pixel([&](int x, int y, const PrimaryHit &, const ShadowStats &) {
            const std::size_t pixel = std::size_t(y) * std::size_t(state.width) + std::size_t(x);
            double sto[3] = {0, 0, 0}, cv[3] = {0, 0, 0};
            for (std::size_t l = 0; l < lights; ++l) {
                const RatioLayers &light = layers[pixel * lights + l];
                for (int c = 0; c < 3; ++c) {
                    sto[c] += double(light.shadowed[c]);  // ratio estimator Eq. 10
                    // ratio estimator Eq. 11: U minus the estimated shadowed-away part.
                    cv[c] +=
                        double(light.analytic[c]) - double(light.unshadowed[c]) + double(light.shadowed[c]);
                }
            }
            set3(stochastic, x, y, Vec3{float(sto[0]), float(sto[1]), float(sto[2])});
            set3(control_variate, x, y, Vec3{float(cv[0]), float(cv[1]), float(cv[2])});
        });
    }

  private:
    RatioLayerCache cache_;
};

}  // namespace

std::unique_ptr<AovAccumulator> make_ratio_group() {
    return std::make_unique<RatioGroup>();
}

std::unique_ptr<AovAccumulator> make_ratio_estimators_group() {
    return std::make_unique<RatioEstimatorsGroup>();
}

}  // namespace aaf::trace
