#pragma once

#include <vector>

#include "aaf/core/contract/aov_contract.h"

/// The roles only AAF (Mehta et al. 2012) writes: its filter width and its
/// sampling plan. Declared by `aaf filter aaf` (methods/aaf/aaf_roles.cpp).
namespace aaf {

namespace roles {
inline constexpr Role FilterWidth{"beta"};        ///< output: AAF beta (AAF Eq. 13)
inline constexpr Role PlannedSpp{"planned_spp"};  ///< output of the sampling plan (AAF Eq. 21)
}  // namespace roles

/// Their channels, units and meanings.
std::vector<RoleInfo> aaf_roles();

}  // namespace aaf
