#pragma once

#include <map>
#include <optional>
#include <string>

#include "aaf/core/contract/aov_set.h"

namespace aaf::cli {

/// The header attributes (attr::kLight*) of the key light that `--light FILE`
/// describes (trace::load_light_file: a scene-format light object or a scene
/// file), or none when `path` is empty. Throws aaf::InputError naming the file.
std::optional<std::map<std::string, AttributeValue>> light_option(const std::string &path);

/// Applies `--light` to an input as read. Precedence (libaaf/RENDERERS.md "A light without a
/// header"): the file's own `aaf:light:*` header is used when there is no
/// `--light`; a `--light` replaces all eight of them (never a mix of the two).
/// Returns true when the file had a light header of its own that was replaced.
bool apply_light_option(const std::optional<std::map<std::string, AttributeValue>> &light, AovSet &aovs);

}  // namespace aaf::cli
