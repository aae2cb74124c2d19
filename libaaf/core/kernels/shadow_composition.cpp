#include "aaf/core/kernels/shadow_composition.h"

#include <vector>

#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

std::array<ConstPlaneView, 3> input3(const MethodImages &images, Role role) {
    return {images.input(role, 0), images.input(role, 1), images.input(role, 2)};
}

std::array<PlaneView, 3> beauty_output(const MethodImages &images) {
    return {images.output(Role::Beauty, 0), images.output(Role::Beauty, 1), images.output(Role::Beauty, 2)};
}

}  // namespace

std::vector<Role> shadow_composition_roles() {
    return {Role::OtherLights, Role::Beauty, Role::KeyLight, Role::Visibility};
}

ShadowBeauty shadow_beauty(const std::map<std::string, AttributeValue> &attributes,
                           const std::function<bool(Role)> &has, Composition composition, bool filters_pass) {
    if (composition == Composition::Paper || !has(Role::Beauty)) return ShadowBeauty::Recomposed;
    // The beauty's own r(x) V(x) is subtracted: the visibility its samples gave.
    if (beauty_holds_exactly(attributes, beauty_holds::kDirect) && has(Role::Visibility))
        return ShadowBeauty::Corrected;
    if (filters_pass && has(Role::KeyLight)) return ShadowBeauty::PassSwapped;
    return ShadowBeauty::Kept;
}

std::string shadow_beauty_note(ShadowBeauty beauty, const std::string &title, bool filters_pass) {
    if (beauty != ShadowBeauty::Kept) return {};
    std::string note =
        "R,G,B left as rendered: the beauty is not the tracer's r(x) V(x) plus the other lights (" +
        std::string(attr::kBeauty) + "), so its key light cannot be told from the rest; " + title +
        "'s filtered visibility is in its own layer";
    if (filters_pass)
        note +=
            "; render the key light alone as a pass (Blender: a light group 'key', Combined_key; "
            "or --map key_light=CHANNELS) to have it filtered and swapped in";
    return note + ", or --compose paper for AAF Eq. 1";
}

void compose_shadowed_beauty(const MethodImages &images, ConstPlaneView filtered_visibility,
                             const PassFilter &filter_pass) {
    const ConstPlaneView noisy_visibility =
        images.has(Role::Visibility) ? images.input(Role::Visibility) : ConstPlaneView{};
    const auto has = [&](Role role) { return images.has(role); };
    const ShadowBeauty how =
        shadow_beauty(images.attributes(), has, images.composition(), static_cast<bool>(filter_pass));
    const std::array<PlaneView, 3> out = beauty_output(images);
    const int width = images.width(), height = images.height();
    if (how == ShadowBeauty::PassSwapped) {
        const std::array<ConstPlaneView, 3> pass = input3(images, Role::KeyLight);
        filter_pass(pass, out);  // the filtered pass, then the rest of the beauty around it
        const std::array<ConstPlaneView, 3> beauty = input3(images, Role::Beauty);
        parallel_for_rows(height, [&](int y) {
            for (std::size_t c = 0; c < 3; ++c)
                for (int x = 0; x < width; ++x) out[c](x, y) += beauty[c](x, y) - pass[c](x, y);
        });
        return;
    }
    const bool other_lights = how == ShadowBeauty::Recomposed && images.has(Role::OtherLights);
    parallel_for_rows(height, [&](int y) {
        for (std::size_t c = 0; c < 3; ++c) {
            const ConstPlaneView r = images.input(Role::Unshadowed, c);
            const PlaneView beauty = out[c];
            switch (how) {
                case ShadowBeauty::Recomposed:
                    for (int x = 0; x < width; ++x)
                        beauty(x, y) = r(x, y) * filtered_visibility(x, y);  // AAF Eq. 1
                    if (other_lights) {
                        const ConstPlaneView other = images.input(Role::OtherLights, c);
                        for (int x = 0; x < width; ++x) beauty(x, y) += other(x, y);
                    }
                    break;
                case ShadowBeauty::Corrected: {
                    // Only r(x) V(x) is replaced: the rest of the beauty (other
                    // lights, anything added after the render) passes through.
                    const ConstPlaneView in = images.input(Role::Beauty, c);
                    for (int x = 0; x < width; ++x)
                        beauty(x, y) = (in(x, y) - r(x, y) * noisy_visibility(x, y)) +
                                       r(x, y) * filtered_visibility(x, y);
                    break;
                }
                default: {
                    const ConstPlaneView in = images.input(Role::Beauty, c);
                    for (int x = 0; x < width; ++x) beauty(x, y) = in(x, y);
                }
            }
        }
    });
}

}  // namespace aaf
