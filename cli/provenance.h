#pragma once

#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"

namespace aaf::cli {

/// Header attributes every `aaf render` and `aaf filter` output records
/// (cli/README.md "Provenance and --skip-existing"); `Software` is set to aaf's.
namespace provenance_attr {
inline constexpr const char *kVersion = "aaf:provenance:version";         // string, "aaf 0.1.0"
inline constexpr const char *kMethod = "aaf:provenance:method";           // string, "render" or the method
inline constexpr const char *kParameters = "aaf:provenance:parameters";   // string, every setting, name=value
inline constexpr const char *kCommand = "aaf:provenance:command";         // string, the command line
inline constexpr const char *kInputsHash = "aaf:provenance:inputs_hash";  // string, 16 hex digits
/// Only on a frame whose method read earlier frames' outputs (ratio --temporal):
/// the frames "S-E" its history reads; inputs_hash then covers their inputs too.
inline constexpr const char *kHistory = "aaf:provenance:history";  // string
}  // namespace provenance_attr

/// The version `aaf --version` prints, "aaf 0.1.0".
const char *aaf_version();

/// Remembers the command line for the outputs' headers: "aaf" and the
/// arguments joined by spaces, less those that cannot change a frame's
/// bytes (-o/--output, --frames, --threads, --progress, --timings,
/// --resume, --checkpoint, --skip-existing, --skip-bad-frames), so that
/// outputs equal by contract (any --threads, a resumed render, a frame made
/// in any chunk of a sequence) stay byte-identical.
void set_command_line(int argc, char **argv);
const std::string &command_line();

/// What an output was made from and how: compared by output_up_to_date().
struct Provenance {
    std::string method;      ///< "render" or the filter method's name
    std::string parameters;  ///< every setting that changes the pixels, "name=value ..."
    std::string inputs_hash;
    std::string history;  ///< provenance_attr::kHistory, "" for none
};

/// FNV-1a hash (16 hex digits) of each file's identity: its size, its
/// modification time and its first 64 KiB (an EXR's header and attributes;
/// a scene's JSON), in order; a missing file hashes as missing. A newer or
/// changed input changes the hash.
std::string inputs_hash(const std::vector<std::string> &files, const std::string &extra = {});

/// Writes `provenance`, the version and the command line into `aovs`' header.
void stamp(const Provenance &provenance, AovSet &aovs);

/// True when `output` is a complete image (every part reads back) whose
/// recorded version, method, parameters and inputs hash equal `expected`,
/// and, for a render, whose aaf:spp_done reaches its aaf:spp
/// (a progressive render's checkpoint is never up to date). Never throws.
bool output_up_to_date(const std::string &output, const Provenance &expected);

}  // namespace aaf::cli
