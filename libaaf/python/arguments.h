#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace aaf::python {

/// Python arguments as C++ values. Each throws aaf::Error naming `what` (the
/// argument, key or attribute) and the type or value it got, so that a bad
/// argument is an aaf.Error, never pybind11's "Unable to cast" RuntimeError.

/// The Python type name of `value` ("int", "NoneType").
std::string type_name_of(const pybind11::handle &value);

/// A str, or when `path_like` a path: a str or any os.PathLike, as os.fsencode gives its bytes.
std::string string_arg(const pybind11::handle &value, const std::string &what, bool path_like = false);

/// An int (a bool is refused) in [low, high].
int int_arg(const pybind11::handle &value, const std::string &what, long long low, long long high);

/// A real number (int or float, not bool); NaN and infinities pass through.
double number_arg(const pybind11::handle &value, const std::string &what);

/// A str (one item) or an iterable of str, e.g. channel names.
std::vector<std::string> string_list_arg(const pybind11::handle &value, const std::string &what);

/// A dict, or what dict() accepts (a mapping, pairs); None is an empty dict.
pybind11::dict dict_arg(const pybind11::handle &value, const std::string &what);

}  // namespace aaf::python
