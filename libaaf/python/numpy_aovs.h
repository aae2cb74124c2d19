#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "aaf/core/contract/aov_set.h"

namespace aaf::python {

/// An AOV set as Python holds it: `channels`, a dict of channel name ->
/// float32 numpy array of shape (height, width) in file order, and
/// `attributes`, a dict of header attribute name -> int, float, str or a
/// 3-tuple of floats (a Vec3, e.g. aaf:light:center).
struct PyAovs {
    pybind11::dict channels;
    pybind11::dict attributes;
};

/// Copies every channel and attribute of `aovs` into new numpy arrays and dicts.
PyAovs to_python(const AovSet &aovs);

/// Copies `aovs` into an AovSet. Throws aaf::Error naming the channel or
/// attribute at fault: no channels, a name that is not a str or is empty, an
/// array that is not 2-D or of another shape than the first, a non-numeric
/// array, an array too large to convert (out of memory), an attribute value
/// of another type than int (32-bit), float (32-bit range), str or a
/// sequence of 3 numbers.
AovSet from_python(const PyAovs &aovs);

/// `value` as the aaf.Aovs it must be; throws aaf::Error naming `what` otherwise.
const PyAovs &aovs_arg(const pybind11::handle &value, const std::string &what);

}  // namespace aaf::python
