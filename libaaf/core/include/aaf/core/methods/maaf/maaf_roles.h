#pragma once

#include <vector>

#include "aaf/core/contract/aov_contract.h"

/// The roles and header attributes of MAAF's 4D soft-shadow filter (Wu et
/// al. 2017): the tracer's maaf group writes them, `aaf filter maaf` reads
/// them (declared in methods/maaf/maaf_roles.cpp).
namespace aaf {

/// N of the MAAF channels the contract lists (MAAF Sec. 6.1: 5 filters per
/// 2D subspace, 25 in 4D); the core API takes any N, the AOV layer is this one.
inline constexpr int kMaafContractPairs = 3;

namespace roles {
/// Samples' light-weighted visibility times the light-side functions (MAAF Eq. 20/23).
inline constexpr Role MaafValueSums{"maaf_value"};
inline constexpr Role MaafUnoccludedSums{"maaf_unoccluded"};  ///< the same, every sample unoccluded
inline constexpr Role MaafWedge{"maaf_wedge"};                ///< the wedge the sums were accumulated with
/// The wedge's slopes' extremes over a temporal window (`--temporal-window`
/// writes them in memory): the widths the sums' phases leave free.
inline constexpr Role MaafWindowWedge{"maaf_window_wedge"};
}  // namespace roles

namespace attr {
inline constexpr const char *kMaafPairs = "aaf:maaf:pairs";  // int, N of the MAAF sums
inline constexpr const char *kMaafOmegaYMax =
    "aaf:maaf:omega_y_max";  // float, rad/m, the light's Omega_y^max of the MAAF sums
}  // namespace attr

/// The (2N-1)^2 channel names of a MAAF sums layer for the contract's N
/// (maaf_accumulation.h's layout), `.R/.G/.B` per channel when `rgb`.
std::vector<std::string> maaf_contract_channels(const std::string &prefix, bool rgb);

/// Their channels, units and meanings.
std::vector<RoleInfo> maaf_roles();

}  // namespace aaf
