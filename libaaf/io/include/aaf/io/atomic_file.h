#pragma once

#include <string>

namespace aaf::io {

/// A temporary path beside `path` (same directory, so the final rename is
/// atomic), unique to this process and call.
std::string temporary_path_for(const std::string &path);

/// Renames `temporary` onto `path`; on failure removes `temporary` and throws
/// aaf::Error "<path>: <problem>".
void commit_temporary(const std::string &temporary, const std::string &path);

}  // namespace aaf::io
