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

}  // namespace aaf
