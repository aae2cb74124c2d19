#pragma once

#include <filesystem>
#include <string>

#include "aaf/core/error.h"

namespace aaf::cli {

/// Refuses to write `output` over `input`: inputs are never modified.
inline void check_not_same_file(const std::string &input, const std::string &output) {
    std::error_code ec;
    if (std::filesystem::exists(output, ec) && std::filesystem::equivalent(input, output, ec))
        throw Error(output + ": output would overwrite the input");
}

}  // namespace aaf::cli
