#include "filtering.h"

#include <memory>
#include <string>
#include <utility>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/framework/progress.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/thread_count.h"
#include "aaf/io/missing_input_report.h"
#include "aaf/trace/aov_group_registry.h"
#include "aaf/trace/light_file.h"
#include "arguments.h"
#include "method_info.h"
#include "numpy_aovs.h"

namespace py = pybind11;

namespace aaf::python {

namespace {

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

/// The `aaf render --aovs` groups that write `role`, for the missing-input recipes.
std::string groups_writing(Role role) {
    return trace::aov_groups_writing({role}).text();
}

/// A Python callable as the filter's ProgressMonitor (OIDN's progress
/// monitor): called with the GIL held, from the thread that runs the filter.
/// It stops the filter by returning False (None or a true value go on) or
/// by raising; its own exception is kept to be raised instead of aaf.Cancelled.
class ProgressCallback {
  public:
    explicit ProgressCallback(py::object callback) : callback_(std::move(callback)) {
        if (!callback_.is_none() && !PyCallable_Check(callback_.ptr()))
            throw Error("progress: expected a callable, got " + type_name_of(callback_));
    }

    ProgressMonitor monitor() {
        if (callback_.is_none()) return {};
        return [this](double fraction_done) {
            py::gil_scoped_acquire gil;
            try {
                const py::object answer = callback_(fraction_done);
                if (answer.is_none()) return true;
                const int truth = PyObject_IsTrue(answer.ptr());
                if (truth < 0) throw py::error_already_set();
                return truth == 1;
            } catch (py::error_already_set &e) {
                raised_ = std::make_unique<py::error_already_set>(std::move(e));
                return false;
            }
        };
    }

    /// Raises what the callback raised, if it did.
    void raise_its_exception() const {
        if (raised_) throw *raised_;
    }

  private:
    py::object callback_;
    std::unique_ptr<py::error_already_set> raised_;
};

PyAovs filter(const py::object &method_name, const py::object &aovs, const py::object &map,
              const py::object &threads_arg, const py::object &light, const py::object &progress_arg,
              const py::object &compose_arg, const py::kwargs &given) {
    const Method &method = find_method(string_arg(method_name, "method"));
    const ParameterSet parameters = parameters_from(method, given);
    const ChannelMap channels = channel_map_from(map);
    const int threads = int_arg(threads_arg, "threads", 0, kMaxThreads);
    // As `aaf filter --compose`.
    const std::string compose = string_arg(compose_arg, "compose");
    if (compose != "correct" && compose != "paper")
        throw ParameterError("compose: '" + compose + "' is neither 'correct' nor 'paper'");
    const Composition composition = compose == "paper" ? Composition::Paper : Composition::Correct;
    ProgressCallback progress(progress_arg);
    AovSet input = from_python(aovs_arg(aovs, "aovs"));
    // As `aaf filter --light`: the file's key light replaces all of the frame's aaf:light:* attributes.
    if (!light.is_none())
        write_light_attributes(trace::load_light_file(string_arg(light, "light", true)), input);
    // The same plan as `aaf filter` makes for this frame: the same method (or
    // delegate) and channels, and every missing input named in one error.
    const FilterPlan plan = prepare_filter(method, parameters, input, channels, composition);
    io::require_plan_inputs(plan, groups_writing);
    AovSet output;
    try {
        py::gil_scoped_release release;
        run_with_threads(threads, [&] { output = run_filter(plan, std::move(input), progress.monitor()); });
    } catch (const Cancelled &) {
        progress.raise_its_exception();
        throw;
    }
    return to_python(output);
}

/// The filter() docstring, generated from the registry like `aaf filter --help`.
std::string filter_doc() {
    std::string doc =
        "filter(method, aovs, *, map=None, threads=0, light=None, progress=None, compose='correct', "
        "**parameters) -> Aovs\n\n"
        "Runs a registered method on `aovs` (as `aaf filter METHOD` does on a file) and returns\n"
        "every input channel plus the method's outputs. `map`: a dict role -> channel name(s), or a\n"
        "list of 'role=channels' (the CLI's --map). `light`: a path to a light file whose key light\n"
        "replaces the aaf:light:* attributes (the CLI's --light). `progress`: called with the fraction\n"
        "done, 0 to 1; returning False (or raising) stops the filter, which raises aaf.Cancelled (or\n"
        "that exception). `compose`: 'correct' replaces only what the method models in the input\n"
        "beauty, 'paper' recomposes R,G,B as the paper does (the CLI's --compose). Missing inputs\n"
        "raise one aaf.InputError naming them all.\n"
        "Parameters by their snake_case names:\n";
    for (const Method *method : methods()) {
        doc += "\n  " + method->info().name + ": " + method->info().summary + "\n";
        for (const ParameterInfo &p : method->info().parameters)
            doc += "    " + p.name + " (" + parameter_type_name(p.type) + ", default " + p.default_value +
                   ", " + p.range_text() + (p.unit.empty() ? "" : ", " + p.unit) + "): " + p.help + "\n";
    }
    return doc;
}

}  // namespace

void def_filtering(py::module_ &m) {
    m.def("filter", &filter, py::arg("method"), py::arg("aovs"), py::kw_only(), py::arg("map") = py::none(),
          py::arg("threads") = 0, py::arg("light") = py::none(), py::arg("progress") = py::none(),
          py::arg("compose") = "correct", filter_doc().c_str());
}

}  // namespace aaf::python
