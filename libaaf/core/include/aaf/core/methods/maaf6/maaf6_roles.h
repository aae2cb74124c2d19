#pragma once

#include <vector>

#include "aaf/core/contract/aov_contract.h"

/// The roles and header attributes of MAAF's combined-effects filter (MAAF
/// Sec. 6.2): the tracer's maaf6 group writes them, `aaf filter maaf6`
/// reads them (declared in methods/maaf6/maaf6_roles.cpp).
namespace aaf {

namespace roles {
inline constexpr Role Maaf6Direct{"maaf6_direct"};  ///< noisy direct radiance (soft shadows through the lens)
inline constexpr Role Maaf6Indirect{"maaf6_indirect"};       ///< noisy one-bounce indirect radiance
inline constexpr Role Maaf6DirectSums{"maaf6_direct_sums"};  ///< direct radiance times the (y, u) functions
inline constexpr Role Maaf6DirectWeights{
    "maaf6_direct_weights"};                                     ///< the same functions alone (normalisation)
inline constexpr Role Maaf6IndirectSums{"maaf6_indirect_sums"};  ///< indirect radiance times the functions
inline constexpr Role Maaf6IndirectWeights{"maaf6_indirect_weights"};  ///< the same functions alone
inline constexpr Role Maaf6Wedge{"maaf6_wedge"};  ///< the 3D wedges the sums were accumulated with
inline constexpr Role Maaf6Spp{"maaf6_spp"};      ///< path samples of the pixel
/// The wedge's slopes' extremes over a temporal window (`--temporal-window`
/// writes them in memory): the widths the sums' phases leave free.
inline constexpr Role Maaf6WindowWedge{"maaf6_window_wedge"};
}  // namespace roles

namespace attr {
inline constexpr const char *kMaaf6Pairs = "aaf:maaf6:pairs";                     // int, N of the maaf6 sums
inline constexpr const char *kMaaf6OmegaDirect = "aaf:maaf6:omega_y_direct";      // float, rad/m, light band
inline constexpr const char *kMaaf6OmegaIndirect = "aaf:maaf6:omega_y_indirect";  // float, rad, bounce band
inline constexpr const char *kMaaf6OmegaLens = "aaf:maaf6:omega_u";               // float, rad/m, 0 = pinhole
inline constexpr const char *kMaaf6Effects = "aaf:maaf6:effects";  // string, e.g. "defocus,shadows,indirect"
/// The maaf6 group's timings, handed to render_scene() in memory, which
/// moves them into trace::RenderTimings: never written to a file.
inline constexpr const char *kMaaf6SamplingS = "aaf:maaf6:sampling_s";    // float, seconds tracing paths
inline constexpr const char *kMaaf6PrefilterS = "aaf:maaf6:prefilter_s";  // float, seconds wedges + sums
}  // namespace attr

/// Their channels, units and meanings.
std::vector<RoleInfo> maaf6_roles();

}  // namespace aaf
