#pragma once

#include <array>
#include <functional>
#include <map>
#include <string>

#include "aaf/core/framework/method.h"

namespace aaf {

/// How a method that filters the key light's visibility (AAF, MAAF, ISG
/// shadows, the Gaussian baseline) makes its beauty, from what the frame holds.
enum class ShadowBeauty {
    /// AAF Eq. 1: r(x) times the filtered visibility, plus the other lights
    /// (Composition::Paper, or a frame without a beauty).
    Recomposed,
    /// The input beauty less r(x) times the noisy visibility, plus r(x) times
    /// the filtered one: the tracer's beauty holds exactly r(x) V(x) (attr::kBeauty).
    Corrected,
    /// Another renderer's beauty less its own pass P of the key light
    /// (Role::KeyLight), plus P filtered with the method's widths.
    PassSwapped,
    /// The input beauty as it was: it is another renderer's and has no pass of
    /// the key light alone to replace; the estimate is in the method's own layers.
    Kept,
};

/// Filters another renderer's pass of the key light (three planes) with the
/// method's own widths and rejection.
using PassFilter =
    std::function<void(const std::array<ConstPlaneView, 3> &pass, const std::array<PlaneView, 3> &filtered)>;

/// The beauty a frame gets: `has` tells the roles found, `filters_pass`
/// whether the method can filter a pass of the key light.
ShadowBeauty shadow_beauty(const std::map<std::string, AttributeValue> &attributes,
                           const std::function<bool(Role)> &has, Composition composition, bool filters_pass);

/// Method::composition_note of a visibility filter (`title`, e.g. "AAF").
std::string shadow_beauty_note(ShadowBeauty beauty, const std::string &title, bool filters_pass);

/// Writes Role::Beauty of `images` as shadow_beauty() decides, from the
/// filtered visibility and the beauty's own (Role::Visibility); `filter_pass`
/// filters Role::KeyLight for ShadowBeauty::PassSwapped (methods without one
/// keep such a beauty).
void compose_shadowed_beauty(const MethodImages &images, ConstPlaneView filtered_visibility,
                             const PassFilter &filter_pass = {});

/// The roles compose_shadowed_beauty() reads when present, for a method's MethodRoles::optional.
std::vector<Role> shadow_composition_roles();

}  // namespace aaf
