#include <type_traits>

#include "../surface_texture.h"
#include "aov_groups.h"

namespace aaf::trace {

namespace {

/// A group that copies one value of the primary hit per pixel, 0 where
/// nothing was hit: it needs no samples.
template <typename Value>
class PrimaryHitGroup final : public AovAccumulator {
  public:
    using Getter = Value (*)(const PrimaryHit &);
    PrimaryHitGroup(const char *name, const char *contents, Role role, Precision precision, Getter value)
        : name_(name), contents_(contents), role_(role), precision_(precision), value_(value) {}

    AovGroupInfo info() const override { return group_info(name_, contents_, roles()); }
    std::vector<Role> roles() const override { return {role_}; }

    void write(const RenderState &state, AovSet &aovs) const override {
        const auto views = add_role_channels(aovs, role_, precision_);
        state.for_each_pixel([&](int x, int y, const PrimaryHit &p, const ShadowStats &) {
            if (!p.found) return;
            if constexpr (std::is_same_v<Value, Vec3>)
                set3(views, x, y, value_(p));
            else
                views[0](x, y) = value_(p);
        });
    }

  private:
    const char *name_, *contents_;
    Role role_;
    Precision precision_;
    Getter value_;
};

}  // namespace

std::unique_ptr<AovAccumulator> make_position_group() {
    return std::make_unique<PrimaryHitGroup<Vec3>>("position", "P.X, P.Y, P.Z", Role::Position,
                                                   Precision::Float,
                                                   [](const PrimaryHit &p) { return p.position; });
}

std::unique_ptr<AovAccumulator> make_normal_group() {
    return std::make_unique<PrimaryHitGroup<Vec3>>("normal", "N.X, N.Y, N.Z", Role::Normal, Precision::Float,
                                                   [](const PrimaryHit &p) { return p.normal; });
}

std::unique_ptr<AovAccumulator> make_object_id_group() {
    return std::make_unique<PrimaryHitGroup<float>>(
        "id", "id.object", Role::ObjectId, Precision::Float,
        [](const PrimaryHit &p) { return float(p.mesh->object_id); });
}

std::unique_ptr<AovAccumulator> make_unshadowed_group() {
    return std::make_unique<PrimaryHitGroup<Vec3>>("unshadowed", "unshadowed.R, unshadowed.G, unshadowed.B",
                                                   Role::Unshadowed, Precision::Float,
                                                   [](const PrimaryHit &p) { return p.unshadowed; });
}

std::unique_ptr<AovAccumulator> make_depth_group() {
    return std::make_unique<PrimaryHitGroup<float>>("depth", "Z", Role::Depth, Precision::Float,
                                                    [](const PrimaryHit &p) { return p.depth_m; });
}

// Reflectances in [0, 1] need no more than half's 11 bits; the beauty stays
// float, since references are compared to 1e-4. A textured material's albedo
// at the primary hit.
std::unique_ptr<AovAccumulator> make_albedo_group() {
    return std::make_unique<PrimaryHitGroup<Vec3>>(
        "albedo", "albedo.R, albedo.G, albedo.B", Role::Albedo, Precision::Half, [](const PrimaryHit &p) {
            return texture_surface(p.mesh->material, p.position, p.normal).material.albedo;
        });
}

}  // namespace aaf::trace
