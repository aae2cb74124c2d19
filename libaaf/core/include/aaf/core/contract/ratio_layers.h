#pragma once

#include <map>
#include <string>

#include "aaf/core/contract/aov_contract.h"

namespace aaf {

/// True for the ratio estimator's roles (ratio_u, ratio_s, ratio_un and the
/// luminance variants), which a renderer may also write once per light
/// (libaaf/AOV_CONTRACT.md: ratio.L<i>.*, i < attr::kRatioLights).
bool is_per_light_role(Role role);

/// Light `light`'s name of a summed ratio channel: the first "ratio." token
/// (at the start, or after a '.' as behind a view-layer prefix) becomes
/// "ratio.L<light>.", so "ratio.S.R" -> "ratio.L0.S.R" and
/// "ViewLayer.ratio.U.G" -> "ViewLayer.ratio.L2.U.G". A name without that
/// token (a --map override) gets "L<light>." before its last component.
std::string per_light_channel(const std::string &channel, int light);

/// The number of lights with their own ratio layers: the int attribute
/// attr::kRatioLights, 0 when absent. Throws aaf::InputError when it is
/// present but not a non-negative int, or declares more lights than a file
/// of `channel_count` channels can hold layers for.
int ratio_light_count(const std::map<std::string, AttributeValue> &attributes, std::size_t channel_count);

}  // namespace aaf
