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

/// An Error caused by the call's parameters not fitting its input rather
/// than by a file: a parameter given for a method that hands this input to a
/// delegate, which does not take it. The CLI exits with code 2 (usage) for
/// these, as for a bad option.
class ParameterError : public Error {
  public:
    explicit ParameterError(const std::string &message) : Error(message) {}
};

/// Runs `work` and returns what it returns, prefixing any aaf::Error's
/// message with `context` (a file name) as "<context>: <message>" and keeping
/// its kind, so that a caller can still tell input errors apart.
template <typename Work>
auto with_context(const std::string &context, const Work &work) {
    try {
        return work();
    } catch (const InputError &e) {
        throw InputError(context + ": " + e.what());
    } catch (const ParameterError &e) {
        throw ParameterError(context + ": " + e.what());
    } catch (const Error &e) {
        throw Error(context + ": " + e.what());
    }
}

}  // namespace aaf
