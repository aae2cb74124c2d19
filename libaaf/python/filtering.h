#pragma once

#include <pybind11/pybind11.h>

namespace aaf::python {

/// Defines filter(): a registered method on an aaf.Aovs, as `aaf filter`
/// runs it on a file (the same plan, --map, --light and missing-input report).
void def_filtering(pybind11::module_ &m);

}  // namespace aaf::python
