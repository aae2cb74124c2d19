#include "numpy_aovs.h"

#include <algorithm>
#include <string>

#include "aaf/core/error.h"

namespace py = pybind11;

namespace aaf::python {

namespace {

py::object attribute_to_python(const AttributeValue &value) {
    if (const int *i = std::get_if<int>(&value)) return py::int_(*i);
    if (const float *f = std::get_if<float>(&value)) return py::float_(*f);
    if (const std::string *s = std::get_if<std::string>(&value)) return py::str(*s);
    const Vec3 &v = std::get<Vec3>(value);
    return py::make_tuple(v.x, v.y, v.z);
}

AttributeValue attribute_from_python(const std::string &name, const py::handle &value) {
    // bool is a subclass of int in Python: stored as 0/1, like aaf:cosine_falloff.
    if (py::isinstance<py::int_>(value)) return AttributeValue(value.cast<int>());
    if (py::isinstance<py::float_>(value)) return AttributeValue(value.cast<float>());
    if (py::isinstance<py::str>(value)) return AttributeValue(value.cast<std::string>());
    if (py::isinstance<py::sequence>(value) && py::len(value) == 3) {
        const auto xyz = value.cast<py::sequence>();
        try {
            return AttributeValue(Vec3(xyz[0].cast<float>(), xyz[1].cast<float>(), xyz[2].cast<float>()));
        } catch (const py::cast_error &) {
        }
    }
    throw Error("attribute '" + name + "': expected int, float, str or 3 numbers, got " +
                std::string(py::str(value.get_type().attr("__name__"))));
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
    if (py::len(aovs.channels) == 0) throw Error("no channels");
    AovSet set;
    bool first = true;
    for (const auto &entry : aovs.channels) {
        const std::string name = entry.first.cast<std::string>();
        py::array_t<float, py::array::c_style | py::array::forcecast> array;
        try {
            array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(entry.second);
        } catch (const py::error_already_set &) {
        }
        if (!array) throw Error("channel '" + name + "': not an array of numbers");
        if (array.ndim() != 2)
            throw Error("channel '" + name + "': expected a 2-D (height, width) array, got " +
                        std::to_string(array.ndim()) + "-D");
        const int height = int(array.shape(0)), width = int(array.shape(1));
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
    }
    for (const auto &entry : aovs.attributes) {
        const std::string name = entry.first.cast<std::string>();
        set.attributes[name] = attribute_from_python(name, entry.second);
    }
    return set;
}

}  // namespace aaf::python
