#include "arguments.h"

#include <climits>

#include "aaf/core/util/error.h"

namespace py = pybind11;

namespace aaf::python {

std::string type_name_of(const py::handle &value) {
    return py::str(py::type::handle_of(value).attr("__name__"));
}

std::string string_arg(const py::handle &value, const std::string &what, bool path_like) {
    // A str or any os.PathLike (its os.fspath a str or bytes), as the bytes
    // open() would use: os.fsencode, so a name that is not UTF-8 works too.
    if (path_like && (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"))) {
        try {
            return py::module_::import("os").attr("fsencode")(value).cast<std::string>();
        } catch (const py::error_already_set &e) {
            throw Error(what + ": " + std::string(py::str(e.value())));
        }
    }
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    throw Error(what + ": expected " + (path_like ? "a path (str or os.PathLike)" : "a str") + ", got " +
                type_name_of(value));
}

int int_arg(const py::handle &value, const std::string &what, long long low, long long high) {
    if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
        throw Error(what + ": expected an int, got " + type_name_of(value));
    int overflow = 0;
    const long long number = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0 || number < low || number > high)
        throw Error(what + ": " + std::string(py::str(value)) + " is outside [" + std::to_string(low) + ", " +
                    std::to_string(high) + "]");
    return int(number);
}

double number_arg(const py::handle &value, const std::string &what) {
    if (py::isinstance<py::bool_>(value) ||
        !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)))
        throw Error(what + ": expected a number, got " + type_name_of(value));
    const double number = PyFloat_AsDouble(value.ptr());
    if (number == -1.0 && PyErr_Occurred()) {  // an int beyond a double's range
        PyErr_Clear();
        throw Error(what + ": " + std::string(py::str(value)) + " is too large for a number");
    }
    return number;
}

std::vector<std::string> string_list_arg(const py::handle &value, const std::string &what) {
    if (py::isinstance<py::str>(value)) return {value.cast<std::string>()};
    if (!py::isinstance<py::iterable>(value) || py::isinstance<py::bytes>(value) ||
        py::isinstance<py::dict>(value))
        throw Error(what + ": expected a str or a list of str, got " + type_name_of(value));
    std::vector<std::string> items;
    for (const py::handle item : value) {
        if (!py::isinstance<py::str>(item))
            throw Error(what + ": expected a list of str, got an item of type " + type_name_of(item));
        items.push_back(item.cast<std::string>());
    }
    return items;
}

py::dict dict_arg(const py::handle &value, const std::string &what) {
    if (value.is_none()) return py::dict();
    if (py::isinstance<py::dict>(value)) return py::reinterpret_borrow<py::dict>(value);
    try {
        return py::dict(py::reinterpret_borrow<py::object>(value));
    } catch (const py::error_already_set &) {
        throw Error(what + ": expected a dict, got " + type_name_of(value));
    }
}

}  // namespace aaf::python
