#include "aov_groups.h"

namespace aaf::trace {

namespace {

/// Screen motion of each pixel's surface point since the previous frame.
class MotionGroup final : public AovAccumulator {
  public:
    AovGroupInfo info() const override { return group_info("motion", "motion.X, motion.Y", roles()); }
    std::vector<Role> roles() const override { return {Role::Motion}; }

    void write(const RenderState &state, AovSet &aovs) const override {
        // The camera and the object's own translation move the surface
        // point on screen. Motion of a few pixels needs no more than half's 11 bits.
        const auto motion = add_role_channels(aovs, Role::Motion, Precision::Half);
        // Both positions are projected the same way, so a still camera and object give exactly 0.
        state.for_each_pixel([&](int x, int y, const PrimaryHit &p, const ShadowStats &) {
            if (!p.found) return;
            const Vec3 before_m = p.mesh ? p.position - p.mesh->moved_since_previous_frame_m : p.position;
            float now_x, now_y, before_x, before_y;
            if (!state.scene.camera.raster_of(p.position, now_x, now_y) ||
                !state.previous_camera.raster_of(before_m, before_x, before_y))
                return;
            motion[0](x, y) = now_x - before_x;
            motion[1](x, y) = now_y - before_y;
        });
    }
};

}  // namespace

std::unique_ptr<AovAccumulator> make_motion_group() {
    return std::make_unique<MotionGroup>();
}

}  // namespace aaf::trace
