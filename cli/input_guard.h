#pragma once

#include <filesystem>
#include <string>

#include "aaf/core/error.h"

namespace aaf::cli {

/// Refuses to write `output` over `input`: inputs are never modified.
inline void check_not_same_file(const std::string &input, const std::string &output) {
    std::error_code ec;
    if (std::filesystem::exists(output, ec) && std::filesystem::equivalent(input, output, ec))
        throw InputError(output + ": output would overwrite the input");
}

/// Runs `work`, prefixing any aaf::Error's message with `context` (a file
/// name) and keeping its kind, so the exit code still tells input errors apart.
template <typename Work>
auto with_context(const std::string &context, const Work &work) {
    try {
        return work();
    } catch (const InputError &e) {
        throw InputError(context + ": " + e.what());
    } catch (const Error &e) {
        throw Error(context + ": " + e.what());
    }
}

}  // namespace aaf::cli
