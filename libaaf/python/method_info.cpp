#include "method_info.h"

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/instruction_set.h"
#include "arguments.h"

namespace py = pybind11;

namespace aaf::python {

const char *parameter_type_name(ParameterType type) {
    switch (type) {
        case ParameterType::Float:
            return "float";
        case ParameterType::Int:
            return "int";
        case ParameterType::Bool:
            return "bool";
        case ParameterType::Choice:
            return "choice";
        case ParameterType::Text:
            return "text";
    }
    return "?";
}

namespace {

py::list role_keys(const std::vector<Role> &roles) {
    py::list keys;
    for (Role role : roles) keys.append(role.key);
    return keys;
}

/// The default as a value of the parameter's type (a float, int or bool; a
/// str for a choice or text), parsed by Python from the declared text.
py::object typed_default(const ParameterInfo &p) {
    const py::str text(p.default_value);
    switch (p.type) {
        case ParameterType::Float:
            return py::float_(text);
        case ParameterType::Int:
            return py::int_(text);
        case ParameterType::Bool:
            return py::bool_(p.default_value == "true");
        case ParameterType::Choice:
        case ParameterType::Text:
            break;
    }
    return std::move(text);
}

/// A method's declaration as a dict: what `aaf info` and `aaf filter --help` print.
py::dict describe(const Method &method) {
    const MethodInfo &info = method.info();
    py::list parameters;
    for (const ParameterInfo &p : info.parameters) {
        py::dict parameter;
        parameter["name"] = p.name;
        parameter["type"] = parameter_type_name(p.type);
        parameter["default"] = typed_default(p);
        parameter["unit"] = p.unit;
        parameter["range"] = p.range_text();
        parameter["help"] = p.help;
        parameter["choices"] = p.choices;
        parameters.append(parameter);
    }
    py::dict d;
    d["name"] = info.name;
    d["title"] = info.title;
    d["summary"] = info.summary;
    d["reference"] = info.reference;
    d["required"] = role_keys(info.roles.required);
    d["optional"] = role_keys(info.roles.optional);
    d["outputs"] = role_keys(info.roles.outputs);
    d["parameters"] = parameters;
    d["required_attributes"] = info.required_attributes;
    return d;
}

void pin_instruction_set(const py::object &name_arg) {
    const std::string name = string_arg(name_arg, "name");
    const std::optional<InstructionSet> set = parse_instruction_set(name);
    if (!set) throw Error("name: unknown instruction set '" + name + "' (" + instruction_set_choices() + ")");
    set_instruction_set(*set);
}

}  // namespace

void def_method_info(py::module_ &m) {
    m.def(
        "methods",
        [] {
            py::list list;
            for (const Method *method : methods()) list.append(describe(*method));
            return list;
        },
        "Every registered method: name, title, summary, reference, roles (required, optional, outputs), "
        "parameters (name, type, default, unit, range, help, choices; the default a float, int, bool or "
        "str as the type says) and required header attributes.");
    m.def(
        "method", [](const py::object &name) { return describe(find_method(string_arg(name, "name"))); },
        py::arg("name"),
        "One registered method, as methods() describes it; raises aaf.Error for an unknown name.");
    m.def("set_instruction_set", &pin_instruction_set, py::arg("name"),
          "Pins the widest instruction set of Embree and the filter kernels, as `aaf --isa`: 'native' (the "
          "fastest this CPU runs, the default unless $AAF_ISA names another), 'sse4.2', 'avx2' or 'avx512'; "
          "raises aaf.Error for an unknown name or one this CPU cannot run.");
    m.def(
        "instruction_set", [] { return std::string(instruction_set_name(instruction_set())); },
        "The instruction set pinned by set_instruction_set() or $AAF_ISA ('native' when neither).");
}

}  // namespace aaf::python
