#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/util/error.h"
#include "aaf/io/exr_io.h"
#include "commands.h"
#include "suggestion.h"

namespace aaf::cli {

/// A CLI11 check that the value is a finite number x with `low` < x (or
/// `low` <= x when `low_allowed`) and x <= `high`. CLI11's own Range and
/// PositiveNumber let NaN through; a failed check is a usage error (exit 2).
inline CLI::Validator finite_number(double low, double high = HUGE_VAL, bool low_allowed = false) {
    const std::string bounds = std::isinf(low) && std::isinf(high)
                                   ? std::string()
                                   : std::string(" in ") + (low_allowed ? "[" : "(") +
                                         CLI::detail::to_string(low) + ", " +
                                         (std::isinf(high) ? "inf)" : CLI::detail::to_string(high) + "]");
    return CLI::Validator(
        [low, high, low_allowed, bounds](std::string &text) -> std::string {
            double value = 0;
            const bool number = CLI::detail::lexical_cast(text, value);
            if (number && std::isfinite(value) && (low_allowed ? value >= low : value > low) && value <= high)
                return {};
            return "'" + text + "' is not a finite number" + bounds;
        },
        "NUMBER" + bounds);
}

/// A CLI11 check for an unsigned seed: CLI11 would read "-1" into it as
/// 2^64 - 1, so a negative seed is a usage error (exit 2) naming the option.
inline CLI::Validator non_negative_seed() {
    return CLI::Validator(
        [](std::string &value) {
            return value.find('-') == std::string::npos ? std::string() : "must not be negative";
        },
        "");
}

/// Adds the options every command that reads AOVs shares: `--map` overrides
/// and `--threads`.
inline void add_map_and_threads_options(CLI::App &cmd, std::vector<std::string> &maps, int &threads) {
    cmd.add_option(
        "--map", maps,
        "Override a channel name: role=channel[,channel...], or role=LAYER for a multi-channel role "
        "(LAYER replaces the role's layer: position=Pw reads Pw.X/Y/Z, ratio_u=myU myU.R/G/B)");
    cmd.add_option("--threads", threads, "Worker threads, 0 = all, at most 1024 (output is identical)")
        ->check(finite_number(0, 1024, /*low_allowed=*/true))
        ->capture_default_str();
}

/// The default channel map with every `--map role=channel` override applied;
/// a bad override is a usage error.
/// `--half` and `--compression`: how an EXR output is stored (io::WriteOptions),
/// the same for every command that writes one; `applies_to` says which images.
inline void add_write_options(CLI::App &cmd, io::WriteOptions &write, const std::string &applies_to) {
    cmd.add_flag("--half", write.half_colour,
                 "Store colour layers (beauty, unshadowed, albedo, unclaimed LAYER.R/G/B/A) of " +
                     applies_to + " as half; data layers (P, N, ... whatever their names) stay float");
    cmd.add_option(
           "--compression", write.compression,
           "EXR compression of " + applies_to +
               ": zip:1 (ZIP at deflate level 1, fast, for intermediates), zip (level 4, OpenEXR's default, "
               "smaller), zip:N "
               "or zips:N (level N, 1-9), zips, piz, rle, none, or the lossy dwaa/dwab (colour layers "
               "only: the data layers then go to a ZIP part named 'data')")
        ->check(CLI::Validator(
            [](const std::string &name) {
                return io::is_known_compression(name) ? std::string() : "unknown compression '" + name + "'";
            },
            "COMPRESSION"))
        ->capture_default_str();
}

inline ChannelMap channel_map_from(const std::vector<std::string> &specs) {
    ChannelMap map;
    for (const std::string &spec : specs) try {
            map.set_override(spec);
        } catch (const Error &e) {
            std::vector<std::string> keys;
            for (const RoleInfo &info : role_table()) keys.push_back(info.role.key);
            const std::string key = spec.substr(0, spec.find('='));
            const bool known = std::find(keys.begin(), keys.end(), key) != keys.end();
            throw UsageError(std::string("--map: ") + e.what() + (known ? "" : did_you_mean(key, keys)));
        }
    return map;
}

/// Refuses an `option` path that does not end in .png (any case): PNG bytes
/// under an .exr name (or any other) make a file every reader misreads.
inline void require_png_name(const std::string &path, const std::string &option) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char &c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (extension != ".png")
        throw UsageError(option + ": '" + path + "' must end in .png (a PNG is written there)");
}

/// Refuses a preview `option` path other than .png, .jpg or .jpeg (any
/// case), the formats the preview writes (chosen by the extension).
inline void require_display_image_name(const std::string &path, const std::string &option) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char &c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (extension != ".png" && extension != ".jpg" && extension != ".jpeg")
        throw UsageError(option + ": '" + path + "' must end in .png, .jpg or .jpeg (the format written)");
}

/// Refuses an output named for a format other than OpenEXR (x.png, x.jpg,
/// x.tif...) from a command that writes only EXR, rather than put EXR bytes
/// under a name every reader misreads. Other names (no extension) pass.
inline void require_exr_output(const std::string &path, const std::string &command) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char &c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char *image :
         {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".hdr", ".bmp", ".gif", ".webp", ".tga"})
        if (extension == image)
            throw UsageError("--output: '" + path + "': " + command + " writes OpenEXR; name it .exr" +
                             " (aaf preview writes PNG or JPEG)");
}

/// The text of `option` when it was given on the command line (even as ''),
/// else nullopt.
inline std::optional<std::string> given(const CLI::Option *option, const std::string &text) {
    return option->count() > 0 ? std::optional<std::string>(text) : std::nullopt;
}

}  // namespace aaf::cli
