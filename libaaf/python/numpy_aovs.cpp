#include "numpy_aovs.h"

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>
#include <new>
#include <string>

#include "aaf/core/util/error.h"
#include "arguments.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace aaf::python {

namespace {

py::object attribute_to_python(const AttributeValue &value) {
    if (const int *i = std::get_if<int>(&value)) return py::int_(*i);
    if (const float *f = std::get_if<float>(&value)) return py::float_(*f);
    if (const std::string *s = std::get_if<std::string>(&value)) return py::str(*s);
    const Vec3 &v = std::get<Vec3>(value);
    return py::make_tuple(v.x, v.y, v.z);
}

/// A float attribute: EXR stores 32-bit floats, so a finite double beyond
/// their range would silently become an infinity.
float float_attribute(const std::string &name, const py::handle &value) {
    const double number = number_arg(value, "attribute '" + name + "'");
    if (std::isfinite(number) && std::fabs(number) > FLT_MAX)
        throw Error("attribute '" + name + "': " + std::string(py::str(value)) +
                    " is outside the range of a 32-bit float");
    return float(number);
}

AttributeValue attribute_from_python(const std::string &name, const py::handle &value) {
    // bool is a subclass of int in Python: stored as 0/1, like aaf:cosine_falloff.
    // EXR int attributes are 32-bit.
    if (py::isinstance<py::int_>(value)) {
        int overflow = 0;
        const long long number = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
        if (overflow != 0 || number < INT_MIN || number > INT_MAX)
            throw Error("attribute '" + name + "': " + std::string(py::str(value)) +
                        " does not fit a 32-bit int (store it as a float or a str)");
        return AttributeValue(int(number));
    }
    if (py::isinstance<py::float_>(value)) return AttributeValue(float_attribute(name, value));
    if (py::isinstance<py::str>(value)) return AttributeValue(value.cast<std::string>());
    if (py::isinstance<py::sequence>(value) && !py::isinstance<py::bytes>(value) && py::len(value) == 3) {
        const auto xyz = py::reinterpret_borrow<py::sequence>(value);
        const auto is_number = [](const py::handle &item) {
            return (py::isinstance<py::int_>(item) || py::isinstance<py::float_>(item)) &&
                   !py::isinstance<py::bool_>(item);
        };
        if (is_number(xyz[0]) && is_number(xyz[1]) && is_number(xyz[2]))
            return AttributeValue(Vec3(float_attribute(name, xyz[0]), float_attribute(name, xyz[1]),
                                       float_attribute(name, xyz[2])));
    }
    throw Error("attribute '" + name + "': expected int, float, str or 3 numbers, got " +
                type_name_of(value));
}

/// `value` as a C-contiguous float32 (height, width) array. Numbers only:
/// bool, int, uint or float dtypes; an allocation that fails is reported as
/// such, not as a wrong type.
py::array_t<float, py::array::c_style> channel_array(const std::string &name, const py::handle &value) {
    const py::module_ numpy = py::module_::import("numpy");
    const std::string what = "channel '" + name + "'";
    py::object array;
    try {
        array = numpy.attr("asarray")(value);
    } catch (const py::error_already_set &e) {
        if (e.matches(PyExc_MemoryError)) throw Error(what + ": out of memory reading it as an array");
        throw Error(what + ": not an array of numbers (" + type_name_of(value) + ")");
    }
    const std::string kind = py::str(array.attr("dtype").attr("kind"));
    if (kind != "b" && kind != "i" && kind != "u" && kind != "f")
        throw Error(what + ": not an array of numbers (dtype " + std::string(py::str(array.attr("dtype"))) +
                    ")");
    const auto numbers = py::reinterpret_borrow<py::array>(array);
    if (numbers.ndim() != 2)
        throw Error(what + ": expected a 2-D (height, width) array, got " + std::to_string(numbers.ndim()) +
                    "-D");
    const py::ssize_t shape[2] = {numbers.shape(0), numbers.shape(1)};
    if (shape[0] <= 0 || shape[1] <= 0 || shape[0] > INT_MAX || shape[1] > INT_MAX)
        throw Error(what + ": shape (" + std::to_string(shape[0]) + ", " + std::to_string(shape[1]) +
                    ") is not an image size (each side 1 to " + std::to_string(INT_MAX) + ")");
    try {
        return numpy.attr("ascontiguousarray")(array, "dtype"_a = "float32")
            .cast<py::array_t<float, py::array::c_style>>();
    } catch (const py::error_already_set &e) {
        if (e.matches(PyExc_MemoryError))
            throw Error(what + ": out of memory converting the (" + std::to_string(shape[0]) + ", " +
                        std::to_string(shape[1]) + ") array to float32");
        throw Error(what + ": not an array of numbers (" + std::string(py::str(e.value())) + ")");
    }
}

}  // namespace

PyAovs to_python(const AovSet &aovs) {
    PyAovs result;
    const std::size_t pixels = aovs.pixel_count();
    for (std::size_t i = 0; i < aovs.channel_names().size(); ++i) {
        py::array_t<float> array({aovs.height(), aovs.width()});
        std::copy_n(aovs.plane(i).data(), pixels, array.mutable_data());
        result.channels[py::str(aovs.channel_names()[i])] = std::move(array);
    }
    for (const auto &entry : aovs.attributes)
        result.attributes[py::str(entry.first)] = attribute_to_python(entry.second);
    return result;
}

AovSet from_python(const PyAovs &aovs) {
    const py::dict channels = dict_arg(aovs.channels, "channels");
    const py::dict attributes = dict_arg(aovs.attributes, "attributes");
    if (py::len(channels) == 0) throw Error("no channels");
    AovSet set;
    bool first = true;
    for (const auto &entry : channels) {
        if (!py::isinstance<py::str>(entry.first))
            throw Error("channels: a channel name must be a str, got " + type_name_of(entry.first) + " " +
                        std::string(py::repr(entry.first)));
        const std::string name = entry.first.cast<std::string>();
        // An EXR channel needs a name: '' would be read back as another one.
        if (name.empty()) throw Error("channel '': an empty channel name");
        const auto array = channel_array(name, entry.second);
        const int height = int(array.shape(0)), width = int(array.shape(1));
        try {
            if (first) {
                set = AovSet(width, height);
                first = false;
            } else if (width != set.width() || height != set.height()) {
                throw Error("channel '" + name + "': shape (" + std::to_string(height) + ", " +
                            std::to_string(width) + ") differs from the first channel's (" +
                            std::to_string(set.height()) + ", " + std::to_string(set.width()) + ")");
            }
            PlaneView plane = set.add_channel(name);
            std::copy_n(array.data(), set.pixel_count(), plane.data);
        } catch (const std::bad_alloc &) {
            throw Error("channel '" + name + "': out of memory for a " + std::to_string(width) + "x" +
                        std::to_string(height) + " channel");
        }
    }
    for (const auto &entry : attributes) {
        if (!py::isinstance<py::str>(entry.first))
            throw Error("attributes: an attribute name must be a str, got " + type_name_of(entry.first) +
                        " " + std::string(py::repr(entry.first)));
        const std::string name = entry.first.cast<std::string>();
        if (name.empty()) throw Error("attribute '': an empty attribute name");
        set.attributes[name] = attribute_from_python(name, entry.second);
    }
    return set;
}

const PyAovs &aovs_arg(const py::handle &value, const std::string &what) {
    if (!py::isinstance<PyAovs>(value))
        throw Error(what + ": expected an aaf.Aovs, got " + type_name_of(value));
    return value.cast<const PyAovs &>();
}

}  // namespace aaf::python
