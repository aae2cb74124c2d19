// The Python module `aaf`: AOV EXRs as numpy arrays, every registered
// method, and the metrics of `aaf compare`. Everything here converts and
// delegates; what a call does is the library's (and the CLI's) code.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/instruction_set.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/io/compare_files.h"
#include "aaf/io/exr_io.h"
#include "arguments.h"
#include "numpy_aovs.h"

namespace py = pybind11;

namespace aaf::python {

namespace {

const char *type_name(ParameterType type) {
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

py::list role_keys(const std::vector<Role> &roles) {
    py::list keys;
    for (Role role : roles) keys.append(role.key);
    return keys;
}

/// A method's declaration as a dict: what `aaf info` and `aaf filter --help` print.
py::dict describe(const Method &method) {
    const MethodInfo &info = method.info();
    py::list parameters;
    for (const ParameterInfo &p : info.parameters) {
        py::dict parameter;
        parameter["name"] = p.name;
        parameter["type"] = type_name(p.type);
        parameter["default"] = p.default_value;
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

/// `map` as the CLI's --map: a dict role -> channel(s) or a list of "role=channels".
ChannelMap channel_map_from(const py::handle &map) {
    ChannelMap channels;
    if (map.is_none()) return channels;
    if (py::isinstance<py::dict>(map)) {
        for (const auto &entry : py::reinterpret_borrow<py::dict>(map)) {
            const std::string role = string_arg(entry.first, "map: a role");
            std::string names;
            for (const std::string &name : string_list_arg(entry.second, "map['" + role + "']"))
                names += (names.empty() ? "" : ",") + name;
            channels.set_override(role + "=" + names);
        }
    } else {
        for (const std::string &spec : string_list_arg(map, "map")) channels.set_override(spec);
    }
    return channels;
}

/// The method's defaults with the keyword arguments set (names checked by ParameterSet).
ParameterSet parameters_from(const Method &method, const py::kwargs &given) {
    ParameterSet parameters = method.default_parameters();
    for (const auto &entry : given) {
        const std::string name = entry.first.cast<std::string>();
        const py::handle value = entry.second;
        if (py::isinstance<py::bool_>(value))
            parameters.set(name, value.cast<bool>());
        else if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
            parameters.set(name, number_arg(value, "parameter '" + name + "'"));
        else if (py::isinstance<py::str>(value))
            parameters.set(name, value.cast<std::string>());
        else
            throw Error("parameter '" + name + "': expected a number, bool or str, got " +
                        type_name_of(value));
    }
    return parameters;
}

/// `value` as the aaf.Aovs it must be.
const PyAovs &aovs_arg(const py::handle &value, const std::string &what) {
    if (!py::isinstance<PyAovs>(value))
        throw Error(what + ": expected an aaf.Aovs, got " + type_name_of(value));
    return value.cast<const PyAovs &>();
}

/// As the CLI's outputs: a name with another image format's extension is
/// refused rather than written as OpenEXR under that name.
void require_exr_path(const std::string &path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char &c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char *image :
         {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".hdr", ".bmp", ".gif", ".webp", ".tga"})
        if (extension == image) throw Error("path: '" + path + "': aaf.write writes OpenEXR; name it .exr");
}

PyAovs filter(const py::object &method_name, const py::object &aovs, const py::object &map,
              const py::object &threads_arg, const py::kwargs &given) {
    const Method &method = find_method(string_arg(method_name, "method"));
    const ParameterSet parameters = parameters_from(method, given);
    const ChannelMap channels = channel_map_from(map);
    const int threads = int_arg(threads_arg, "threads", 0, kMaxThreads);
    AovSet input = from_python(aovs_arg(aovs, "aovs"));
    // The same plan as `aaf filter` makes for this frame: the same method (or delegate) and channels.
    const FilterPlan plan = prepare_filter(method, parameters, input, channels);
    AovSet output;
    {
        py::gil_scoped_release release;
        run_with_threads(threads, [&] { output = run_filter(plan, std::move(input)); });
    }
    return to_python(output);
}

io::CompareFilesOptions compare_options(const py::object &channels_arg, const py::object &layer,
                                        const py::object &metrics, const py::object &peak_arg) {
    io::CompareFilesOptions options;
    const std::vector<std::string> channels = string_list_arg(channels_arg, "channels");
    if (!channels.empty()) options.channels = channels;
    options.layer = string_arg(layer, "layer");
    for (const std::string &key : string_list_arg(metrics, "metrics")) {
        const io::CompareMetric *metric = io::find_compare_metric(key);
        if (!metric) throw Error("metrics: unknown metric '" + key + "'");
        options.metrics.push_back(metric);
    }
    // As the CLI's --peak: a finite number above zero (a PSNR against 0 or NaN means nothing).
    const double peak = number_arg(peak_arg, "peak");
    if (!std::isfinite(peak) || peak <= 0)
        throw Error("peak: " + std::string(py::str(peak_arg)) + " is not a finite number above 0");
    options.psnr_peak = peak;
    return options;
}

py::dict result_dict(const io::ComparePairResult &result, const io::CompareFilesOptions &options) {
    py::dict d;
    for (const io::CompareMetric *metric : options.metrics) d[metric->key] = result.metrics.*(metric->value);
    d["psnr_peak"] = options.psnr_peak;
    d["channels"] = result.channels;
    d["pixels"] = result.metrics.pixels;
    d["nonfinite_pixels"] = result.metrics.nonfinite_pixels;
    d["spp"] = result.spp;
    return d;
}

/// `aaf compare` of one pair: both file paths, or both AOV sets in memory.
py::dict compare(const py::object &test, const py::object &reference, const py::object &channels,
                 const py::object &layer, const py::object &metrics, const py::object &peak) {
    const io::CompareFilesOptions options = compare_options(channels, layer, metrics, peak);
    io::ComparePairResult result;
    if (!py::isinstance<PyAovs>(test) && !py::isinstance<PyAovs>(reference)) {
        const io::ImagePair pair{"", string_arg(test, "test", true),
                                 string_arg(reference, "reference", true)};
        py::gil_scoped_release release;
        result = io::compare_files({pair}, options).pairs.at(0);
    } else if (py::isinstance<PyAovs>(test) && py::isinstance<PyAovs>(reference)) {
        const AovSet test_set = from_python(test.cast<const PyAovs &>());
        const AovSet reference_set = from_python(reference.cast<const PyAovs &>());
        py::gil_scoped_release release;
        result = io::compare_aov_sets({"", "test", "reference"}, test_set, reference_set, options);
    } else {
        throw Error(std::string(py::isinstance<PyAovs>(test) ? "reference" : "test") +
                    ": test and reference must both be paths or both aaf.Aovs, got " + type_name_of(test) +
                    " and " + type_name_of(reference));
    }
    return result_dict(result, options);
}

/// The filter() docstring, generated from the registry like `aaf filter --help`.
std::string filter_doc() {
    std::string doc =
        "filter(method, aovs, *, map=None, threads=0, **parameters) -> Aovs\n\n"
        "Runs a registered method on `aovs` (as `aaf filter METHOD` does on a file) and returns\n"
        "every input channel plus the method's outputs. `map`: a dict role -> channel name(s), or a\n"
        "list of 'role=channels' (the CLI's --map). Parameters by their snake_case names:\n";
    for (const Method *method : methods()) {
        doc += "\n  " + method->info().name + ": " + method->info().summary + "\n";
        for (const ParameterInfo &p : method->info().parameters)
            doc += "    " + p.name + " (" + type_name(p.type) + ", default " + p.default_value + ", " +
                   p.range_text() + (p.unit.empty() ? "" : ", " + p.unit) + "): " + p.help + "\n";
    }
    return doc;
}

}  // namespace

}  // namespace aaf::python

PYBIND11_MODULE(aaf, m) {
    using namespace aaf;
    using namespace aaf::python;
    m.doc() = "libaaf: image-space reconstruction of ray-traced distribution effects";
    m.attr("__version__") = AAF_VERSION;

    // Translators are tried newest first: InputError before its base Error.
    const py::exception<Error> &error = py::register_exception<Error>(m, "Error");
    py::register_exception<InputError>(m, "InputError", error.ptr());

    py::class_<PyAovs>(m, "Aovs",
                       "channels: dict name -> float32 array (height, width); attributes: dict of header "
                       "attributes (int, float, str, or 3-tuples for vectors)")
        .def(py::init([](py::object channels, py::object attributes) {
                 PyAovs aovs;
                 aovs.channels = dict_arg(channels, "channels");
                 aovs.attributes = dict_arg(attributes, "attributes");
                 return aovs;
             }),
             py::arg("channels") = py::none(), py::arg("attributes") = py::none())
        .def_property(
            "channels", [](const PyAovs &aovs) { return aovs.channels; },
            [](PyAovs &aovs, const py::object &channels) { aovs.channels = dict_arg(channels, "channels"); })
        .def_property(
            "attributes", [](const PyAovs &aovs) { return aovs.attributes; },
            [](PyAovs &aovs, const py::object &attributes) {
                aovs.attributes = dict_arg(attributes, "attributes");
            })
        .def("__repr__", [](const PyAovs &aovs) {
            return "<aaf.Aovs " + std::to_string(py::len(aovs.channels)) + " channels, " +
                   std::to_string(py::len(aovs.attributes)) + " attributes>";
        });

    m.def(
        "read",
        [](const py::object &path_arg) {
            const std::string path = string_arg(path_arg, "path", true);
            AovSet aovs;
            {
                py::gil_scoped_release release;
                aovs = io::read_aovs(path);
            }
            return to_python(aovs);
        },
        py::arg("path"),
        "Reads every channel of an image's first part as float32 arrays, with its header attributes. "
        "Raises aaf.InputError '<path>: <problem>'.");
    m.def(
        "write",
        [](const py::object &path_arg, const py::object &aovs, const py::object &compression,
           const py::object &half) {
            const std::string path = string_arg(path_arg, "path", true);
            require_exr_path(path);
            if (!py::isinstance<py::bool_>(half))
                throw Error("half: expected a bool, got " + type_name_of(half));
            io::WriteOptions options;
            options.compression = string_arg(compression, "compression");
            options.half_colour = half.cast<bool>();
            const AovSet set = with_context(path, [&] { return from_python(aovs_arg(aovs, "aovs")); });
            py::gil_scoped_release release;
            io::write_aovs(set, path, options);
        },
        py::arg("path"), py::arg("aovs"), py::arg("compression") = "zip", py::arg("half") = false,
        "Writes `aovs` as an OpenEXR file (float channels; half=True stores colour layers as half), "
        "atomically; a path named .png, .jpg, .tif or another image format is refused. Raises "
        "aaf.InputError '<path>: <problem>', aaf.Error naming a bad argument.");
    m.def(
        "methods",
        [] {
            py::list list;
            for (const Method *method : methods()) list.append(describe(*method));
            return list;
        },
        "Every registered method: name, title, summary, reference, roles (required, optional, outputs), "
        "parameters (name, type, default, unit, range, help, choices) and required header attributes.");
    m.def(
        "method", [](const py::object &name) { return describe(find_method(string_arg(name, "name"))); },
        py::arg("name"),
        "One registered method, as methods() describes it; raises aaf.Error for an unknown name.");
    m.def(
        "set_instruction_set",
        [](const py::object &name_arg) {
            const std::string name = string_arg(name_arg, "name");
            const std::optional<InstructionSet> set = parse_instruction_set(name);
            if (!set)
                throw Error("name: unknown instruction set '" + name + "' (" + instruction_set_choices() +
                            ")");
            set_instruction_set(*set);
        },
        py::arg("name"),
        "Pins the widest instruction set of Embree and the filter kernels, as `aaf --isa`: 'native' (the "
        "fastest this CPU runs, the default unless $AAF_ISA names another), 'sse4.2', 'avx2' or 'avx512'; "
        "raises aaf.Error for an unknown name or one this CPU cannot run.");
    m.def(
        "instruction_set", [] { return std::string(instruction_set_name(instruction_set())); },
        "The instruction set pinned by set_instruction_set() or $AAF_ISA ('native' when neither).");
    m.def("filter", &filter, py::arg("method"), py::arg("aovs"), py::kw_only(), py::arg("map") = py::none(),
          py::arg("threads") = 0, filter_doc().c_str());
    m.def(
        "metrics",
        [] {
            std::vector<std::string> keys;
            for (const io::CompareMetric &metric : io::compare_metrics()) keys.push_back(metric.key);
            return keys;
        },
        "The metric keys compare() accepts (those of `aaf compare --metric`).");
    m.def("compare", &compare, py::arg("test"), py::arg("reference"), py::kw_only(),
          py::arg("channels") = py::list(), py::arg("layer") = "",
          py::arg("metrics") = std::vector<std::string>{"rmse", "mse", "psnr"}, py::arg("peak") = 1.0,
          "Error of `test` against `reference` as `aaf compare` measures it: two file paths or two "
          "aaf.Aovs. channels: names or 'test=reference' pairs (default R,G,B, the beauty); layer: "
          "compare that layer instead; peak: the PSNR's peak, finite and above 0. Returns a dict of the "
          "metrics, psnr_peak, channels, pixels, "
          "nonfinite_pixels and spp (NaN without the spp AOVs).");
}
