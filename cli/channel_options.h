#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "aaf/core/aov_contract.h"

namespace aaf::cli {

/// Adds the options every command that reads AOVs shares: `--map` overrides
/// and `--threads`.
inline void add_map_and_threads_options(CLI::App &cmd, std::vector<std::string> &maps, int &threads) {
    cmd.add_option("--map", maps, "Override a channel name: role=channel[,channel...]");
    cmd.add_option("--threads", threads, "Worker threads, 0 = all (output is identical)")
        ->capture_default_str();
}

/// The default channel map with every `--map role=channel` override applied.
inline ChannelMap channel_map_from(const std::vector<std::string> &specs) {
    ChannelMap map;
    for (const std::string &spec : specs) map.set_override(spec);
    return map;
}

/// The text of `option` when it was given on the command line (even as ''),
/// else nullopt.
inline std::optional<std::string> given(const CLI::Option *option, const std::string &text) {
    return option->count() > 0 ? std::optional<std::string>(text) : std::nullopt;
}

}  // namespace aaf::cli
