#pragma once

#include <vector>

#include "aaf/core/contract/aov_contract.h"

/// The roles of the ratio estimator (Heitz, Hill, McGuire 2018): the
/// tracer's ratio group writes them, `aaf filter ratio` reads them, per
/// light too (ratio_layers.h; declared in methods/ratio/ratio_roles.cpp).
namespace aaf {

namespace roles {
/// Analytic unshadowed direct light U (ratio estimator Eq. 20).
inline constexpr Role RatioAnalytic{"ratio_u"};
inline constexpr Role RatioShadowed{"ratio_s"};     ///< stochastic shadowed direct light S_N (Eq. 21)
inline constexpr Role RatioUnshadowed{"ratio_un"};  ///< stochastic unshadowed direct light U_N (Eq. 22)
inline constexpr Role RatioShadowedLuminance{"ratio_s_y"};     ///< luminance of S_N (Sec. 3.4)
inline constexpr Role RatioUnshadowedLuminance{"ratio_un_y"};  ///< luminance of U_N (Sec. 3.4)
/// Output: the estimate of the direct light, U den(S_N) / den(U_N) summed over the lights.
inline constexpr Role RatioDirect{"ratio_direct"};
}  // namespace roles

/// Their channels, units and meanings.
std::vector<RoleInfo> ratio_roles();

}  // namespace aaf
