#include "aov_groups.h"

namespace aaf::trace {

namespace {

class BeautyGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override { return group_info("beauty", "R, G, B (always written)", roles()); }
    std::vector<Role> roles() const override { return {Role::Beauty}; }

    void write(const RenderState &state, AovSet &aovs) const override {
        const bool thin_lens = state.scene.camera.is_thin_lens();
        const auto beauty = add_role_channels(aovs, Role::Beauty);
        // What a filter may replace: through a pinhole, exactly r(x) V(x) plus the other lights.
        if (!thin_lens) aovs.attributes[attr::kBeauty] = std::string(beauty_holds::kDirect);
        state.for_each_pixel([&](int x, int y, const PrimaryHit &primary, const ShadowStats &s) {
            if (thin_lens)
                set3(beauty, x, y, s.mean_radiance());  // defocused: the lens rays' radiance
            else if (primary.found)                     // AAF Eq. 1, plus the other lights
                set3(beauty, x, y,
                     primary.unshadowed * s.visibility() +
                         (state.separate_radiance ? s.mean_radiance() : Vec3{}));
        });
    }
};

}  // namespace

std::unique_ptr<AovAccumulator> make_beauty_group() {
    return std::make_unique<BeautyGroup>();
}

}  // namespace aaf::trace
