#pragma once

#include <string>
#include <vector>

namespace aaf::io {

// A thin layer over OpenImageIO's Filesystem sequence functions
// (parse_pattern, enumerate_sequence, enumerate_file_sequence,
// scan_for_matching_filenames) with two rules of its own: ':' is a step like
// 'x' (OIIO ignores it), and n '#' mean n digits (OIIO: one '#' = 4 digits).

/// Frame numbers of a range spec, in the order written, duplicates kept out:
/// "7"; "1-100"; "1-100x2" or "1-100:2" (every 2nd frame from 1); lists of
/// these separated by commas, "1,5,7-9". Throws aaf::Error on a malformed spec,
/// a zero or negative step, or an end before its start.
std::vector<int> parse_frame_range(const std::string &spec);

/// True when `path` names a sequence: a run of `#` or `@`, or a printf
/// `%d` / `%0Nd` field.
bool is_sequence_pattern(const std::string &path);

/// The path of one frame. Padding rule (as Blender, not oiiotool): a run of n
/// `#` (or `@`) is the frame number zero-padded to n digits, so
/// `shot.####.exr` is `shot.0007.exr`; `%04d` pads to 4, `%d` does not pad.
/// Negative frames keep their sign before the padding. Throws aaf::Error when
/// the pattern has no frame field.
std::string frame_path(const std::string &pattern, int frame);

/// Frames of `pattern` that exist on disk, ascending: the directory is listed
/// once and names are matched against the pattern.
std::vector<int> frames_on_disk(const std::string &pattern);

}  // namespace aaf::io
