#include "aaf/core/kernels/shadow_composition.h"

#include <vector>

#include "aaf/core/util/parallel.h"
#include "aaf/core/util/plane_rows.h"

namespace aaf {

namespace {

std::array<ConstPlaneView, 3> input3(const MethodImages &images, Role role) {
    return {images.input(role, 0), images.input(role, 1), images.input(role, 2)};
}

std::array<PlaneView, 3> beauty_output(const MethodImages &images) {
    return {images.output(Role::Beauty, 0), images.output(Role::Beauty, 1), images.output(Role::Beauty, 2)};
}

/// The planes one beauty row is made from (unused ones invalid).
struct CompositionPlanes {
    ShadowBeauty how = ShadowBeauty::Kept;
    std::array<PlaneView, 3> out;
    ConstPlaneView filtered_visibility, noisy_visibility;
    std::array<ConstPlaneView, 3> unshadowed, beauty, pass, other_lights;
};

/// Row y of channel c of the beauty, over contiguous rows (the loops vectorise).
void compose_channel_row(const CompositionPlanes &p, std::size_t c, int y, int width, const float *fv,
                         const float *nv, float *beauty, std::vector<float> (&buffers)[2]) {
    switch (p.how) {
        case ShadowBeauty::Recomposed: {
            const float *const r = contiguous_row(p.unshadowed[c], y, buffers[0]);
            for (int x = 0; x < width; ++x) beauty[x] = r[x] * fv[x];  // AAF Eq. 1
            if (!p.other_lights[c].valid()) break;
            const float *const other = contiguous_row(p.other_lights[c], y, buffers[1]);
            for (int x = 0; x < width; ++x) beauty[x] += other[x];
            break;
        }
        case ShadowBeauty::Corrected: {
            // Only r(x) V(x) is replaced: the rest of the beauty (other
            // lights, anything added after the render) passes through.
            const float *const r = contiguous_row(p.unshadowed[c], y, buffers[0]);
            const float *const in = contiguous_row(p.beauty[c], y, buffers[1]);
            for (int x = 0; x < width; ++x) beauty[x] = (in[x] - r[x] * nv[x]) + r[x] * fv[x];
            break;
        }
        case ShadowBeauty::PassSwapped: {
            // `beauty` holds the filtered pass: the rest of the beauty around it.
            const float *const in = contiguous_row(p.beauty[c], y, buffers[0]);
            const float *const pass = contiguous_row(p.pass[c], y, buffers[1]);
            for (int x = 0; x < width; ++x) beauty[x] += in[x] - pass[x];
            break;
        }
        default: {
            const float *const in = contiguous_row(p.beauty[c], y, buffers[0]);
            for (int x = 0; x < width; ++x) beauty[x] = in[x];
        }
    }
}

/// Row y of the three beauty channels: in place where the output's pixels
/// are adjacent, else through a row buffer.
void compose_row(const CompositionPlanes &p, int y) {
    const int width = p.out[0].width;
    std::vector<float> buffers[2], visibility[2], out_row;
    const float *const fv = p.how == ShadowBeauty::Recomposed || p.how == ShadowBeauty::Corrected
                                ? contiguous_row(p.filtered_visibility, y, visibility[0])
                                : nullptr;
    const float *const nv =
        p.how == ShadowBeauty::Corrected ? contiguous_row(p.noisy_visibility, y, visibility[1]) : nullptr;
    for (std::size_t c = 0; c < 3; ++c) {
        const PlaneView &view = p.out[c];
        float *beauty = &view(0, y);
        if (view.pixel_stride != 1) {
            out_row.resize(std::size_t(width));
            for (int x = 0; x < width; ++x) out_row[std::size_t(x)] = view(x, y);  // PassSwapped adds to it
            beauty = out_row.data();
        }
        compose_channel_row(p, c, y, width, fv, nv, beauty, buffers);
        if (view.pixel_stride != 1)
            for (int x = 0; x < width; ++x) view(x, y) = out_row[std::size_t(x)];
    }
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
    const auto has = [&](Role role) { return images.has(role); };
    const ShadowBeauty how =
        shadow_beauty(images.attributes(), has, images.composition(), static_cast<bool>(filter_pass));
    const std::array<PlaneView, 3> out = beauty_output(images);
    if (how == ShadowBeauty::PassSwapped) {
        const std::array<ConstPlaneView, 3> pass = input3(images, Role::KeyLight);
        filter_pass(pass, out);  // the filtered pass, then the rest of the beauty around it
    }
    // The views are looked up once, not per row.
    CompositionPlanes planes;
    planes.how = how;
    planes.out = out;
    planes.filtered_visibility = filtered_visibility;
    if (images.has(Role::Visibility)) planes.noisy_visibility = images.input(Role::Visibility);
    const bool other_lights = how == ShadowBeauty::Recomposed && images.has(Role::OtherLights);
    for (std::size_t c = 0; c < 3; ++c) {
        if (how == ShadowBeauty::Recomposed || how == ShadowBeauty::Corrected)
            planes.unshadowed[c] = images.input(Role::Unshadowed, c);
        if (how != ShadowBeauty::Recomposed) planes.beauty[c] = images.input(Role::Beauty, c);
        if (how == ShadowBeauty::PassSwapped) planes.pass[c] = images.input(Role::KeyLight, c);
        if (other_lights) planes.other_lights[c] = images.input(Role::OtherLights, c);
    }
    parallel_for_rows(images.width() > 0 ? images.height() : 0, [&](int y) { compose_row(planes, y); });
}

}  // namespace aaf
