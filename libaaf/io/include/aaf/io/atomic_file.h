#pragma once

#include <string>

namespace aaf::io {

/// Refuses to write `output` over `input` (the same file under any name):
/// throws aaf::InputError "<output>: output would overwrite the input".
/// Inputs are never modified.
void check_not_same_file(const std::string &input, const std::string &output);

/// A temporary path beside `path` (same directory, so the final rename is
/// atomic), unique to this process and call: `.NAME.tmp-PID-N`, or, for a
/// NAME too long to take the suffix within 255 bytes, `.PREFIX~HASH.tmp-PID-N`
/// (the first 180 bytes of NAME and a 64-bit hash of all of it). It is
/// remembered until commit_temporary() or discard_temporary(), so that an
/// interrupt can remove it (remove_temporaries_on_signal()).
/// First removes what a killed earlier run left for the same `path`: regular
/// files named exactly as above whose PID is no running process (never
/// another name, never a live writer's file).
/// The temporary is created (empty) here; throws aaf::InputError
/// "<path>: is a directory" when `path` is one, and "<path>: cannot write:
/// <the system's reason>" when the temporary cannot be created.
std::string temporary_path_for(const std::string &path);

/// Renames `temporary` onto `path`; on failure removes `temporary` and throws
/// aaf::Error "<path>: <problem>".
void commit_temporary(const std::string &temporary, const std::string &path);

/// Removes `temporary` (if it was written) and forgets it.
void discard_temporary(const std::string &temporary);

/// Installs SIGINT and SIGTERM handlers that delete every temporary file this
/// process has not committed yet, then end the process by the same signal (so
/// a farm sees the usual 130/143). A killed run leaves no partial file under a
/// final name anyway; this also leaves no hidden `.NAME.tmp-PID-N` behind
/// (only SIGKILL, which cannot be caught, can still leave one; the next write
/// of the same output removes it, see temporary_path_for()).
void remove_temporaries_on_signal();

}  // namespace aaf::io
