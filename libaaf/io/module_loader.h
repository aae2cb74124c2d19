#pragma once

#include <string>

namespace aaf::io {

/// Loads one of aaf's run-time modules (libaaf_formats.so, libaaf_sequences.so)
/// with dlopen and returns what its entry point, a C function taking nothing,
/// returns. The module is looked for beside the executable or library that
/// holds aaf_io, then in the install layout's library folder, then in this
/// build's and the install prefix's. Throws aaf::Error naming the file,
/// `purpose` (what the module does) and why it could not be loaded.
const void *load_module_table(const char *file, const char *entry, const char *purpose);

}  // namespace aaf::io
