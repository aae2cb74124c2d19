#pragma once

#include <pybind11/pybind11.h>

#include "aaf/core/framework/parameters.h"

namespace aaf::python {

/// A parameter type as methods() names it: "float", "int", "bool", "choice", "text".
const char *parameter_type_name(ParameterType type);

/// Defines methods(), method(), set_instruction_set() and instruction_set():
/// what `aaf info` and `aaf --isa` give on the command line.
void def_method_info(pybind11::module_ &m);

}  // namespace aaf::python
