#pragma once

#include <stdexcept>
#include <string>

namespace aaf {

/// The one exception type of libaaf. The message names the offending file,
/// AOV or parameter; library code never prints or exits.
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string &message) : std::runtime_error(message) {}
};

/// An Error caused by an input or output file rather than by the call: an
/// unreadable or unwritable image, a missing channel or header attribute,
/// images of different sizes. The CLI exits with code 3 for these.
class InputError : public Error {
  public:
    explicit InputError(const std::string &message) : Error(message) {}
};

}  // namespace aaf
