#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace aaf {

/// `name` with every byte that is not printable ASCII (and the single quote
/// and backslash) written as \xNN, so that a message quoting a channel or
/// attribute name read from a file stays one readable line whatever bytes
/// the name holds. Printable names come back unchanged.
inline std::string escaped(std::string_view name) {
    std::string out;
    for (const char c : name) {
        const unsigned char byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte < 0x7f && c != '\'' && c != '\\') {
            out += c;
        } else {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02x", byte);
            out += hex;
        }
    }
    return out;
}

/// escaped(`name`) in single quotes: how a message names a channel or attribute.
inline std::string quoted(std::string_view name) {
    return "'" + escaped(name) + "'";
}

}  // namespace aaf
