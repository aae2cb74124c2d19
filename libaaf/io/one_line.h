#pragma once

#include <string>

namespace aaf::io {

/// A library's error text as one line: OpenImageIO joins its messages (and
/// libpng's, OpenEXR's) with newlines, but an error line must stay one line.
/// Line breaks become "; ", other control bytes a space.
inline std::string one_line(const std::string &message) {
    std::string out;
    bool line_break = false;
    for (const char c : message) {
        if (c == '\n' || c == '\r') {
            line_break = true;
            continue;
        }
        if (line_break && !out.empty()) out += "; ";
        line_break = false;
        out += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
    }
    return out;
}

}  // namespace aaf::io
