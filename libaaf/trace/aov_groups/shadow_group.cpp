#include "aov_groups.h"

namespace aaf::trace {

namespace {

/// The key light's shadow as AAF reads it: the light-weighted visibility
/// (AAF Eq. 1), the receiver and occluder distances d1, d2min, d2max (AAF
/// Fig. 2), the samples taken and the pixel's footprint d (AAF Eq. 6); with
/// several lights on a pinhole camera, the other lights' shading beside it.
class ShadowGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override {
        return group_info("shadow",
                          "shadow.V, shadow.d1, shadow.d2min, shadow.d2max, pixel.spp, pixel.size (and "
                          "otherlights.R/G/B with several lights)",
                          roles());
    }
    std::vector<Role> roles() const override {
        return {Role::Visibility,      Role::D1,        Role::D2Min,      Role::D2Max,
                Role::SamplesPerPixel, Role::PixelSize, Role::OtherLights};
    }

    void write(const RenderState &state, AovSet &aovs) const override {
        const LightPlane &light = state.scene.key_light();
        const auto visibility = add_role_channels(aovs, Role::Visibility);
        const auto d1 = add_role_channels(aovs, Role::D1);
        const auto d2_min = add_role_channels(aovs, Role::D2Min);
        const auto d2_max = add_role_channels(aovs, Role::D2Max);
        const auto spp = add_role_channels(aovs, Role::SamplesPerPixel);
        const auto pixel_size = add_role_channels(aovs, Role::PixelSize);
        state.for_each_pixel([&](int x, int y, const PrimaryHit &primary, const ShadowStats &s) {
            visibility[0](x, y) = 1.0f;  // background: visibility 1, distances 0
            spp[0](x, y) = float(s.taken);
            if (!primary.found) return;
            visibility[0](x, y) = s.visibility();
            d1[0](x, y) = light.plane_distance_m(primary.position);
            if (s.occluded_any()) {
                d2_min[0](x, y) = s.d2_min_m;
                d2_max[0](x, y) = s.d2_max_m;
            }
            pixel_size[0](x, y) = primary.pixel_size_m;
        });
        if (state.separate_radiance && !state.scene.camera.is_thin_lens()) {
            const auto other = add_role_channels(aovs, Role::OtherLights);
            state.for_each_pixel([&](int x, int y, const PrimaryHit &, const ShadowStats &s) {
                set3(other, x, y, s.mean_radiance());
            });
        }
    }

    std::vector<std::string> resume_channels() const override {
        return {channel(Role::SamplesPerPixel), channel(Role::D2Min), channel(Role::D2Max)};
    }
    /// The samples taken and the occluder distances; the sums are the progress group's.
    void restore(const AovSet &partial, std::vector<ShadowStats> &stats) override {
        const ConstPlaneView taken = partial.channel(channel(Role::SamplesPerPixel)),
                             d2_min = partial.channel(channel(Role::D2Min)),
                             d2_max = partial.channel(channel(Role::D2Max));
        for (int y = 0; y < partial.height(); ++y)
            for (int x = 0; x < partial.width(); ++x) {
                ShadowStats &s = stats[std::size_t(y) * partial.width() + x];
                s.taken = std::uint32_t(taken(x, y));
                if (d2_max(x, y) > 0) {
                    s.d2_min_m = d2_min(x, y);
                    s.d2_max_m = d2_max(x, y);
                }
            }
    }

  private:
    static const std::string &channel(Role role) { return role_info(role).channels.front(); }
};

}  // namespace

std::unique_ptr<AovAccumulator> make_shadow_group() {
    return std::make_unique<ShadowGroup>();
}

}  // namespace aaf::trace
