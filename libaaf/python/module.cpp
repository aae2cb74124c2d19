// The Python module `aaf`: AOV EXRs as numpy arrays, every registered
// method, and the metrics of `aaf compare`. Everything here converts and
// delegates; what a call does is the library's (and the CLI's) code.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "aaf/core/framework/progress.h"
#include "aaf/core/util/error.h"
#include "aaf/io/compare_files.h"
#include "aaf/io/exr_io.h"
#include "arguments.h"
#include "filtering.h"
#include "method_info.h"
#include "numpy_aovs.h"

namespace py = pybind11;

namespace aaf::python {

namespace {

/// As the CLI's outputs: a name with another image format's extension is
/// refused rather than written as OpenEXR under that name.
void require_exr_path(const std::string &path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char &c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char *image :
         {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".hdr", ".bmp", ".gif", ".webp", ".tga"})
        if (extension == image) throw Error("path: '" + path + "': aaf.write writes OpenEXR; name it .exr");
}

/// Every channel of every part of an AOV EXR, as the file pipeline borrows
/// the channels the first part lacks from the others (a lossy `aaf filter
/// --compression dwaa` output keeps its data channels in a part of their own).
AovSet read_every_part(const std::string &path) {
    io::require_exr_file(path);
    io::ImageLayout layout;
    AovSet aovs = io::read_aovs(path, &layout);
    std::vector<std::string> names;
    for (const io::PartSummary &part : io::other_parts(path, layout))
        names.insert(names.end(), part.channels.begin(), part.channels.end());
    io::add_channels_from_other_parts(path, layout, names, aovs);
    return aovs;
}

PyAovs read(const py::object &path_arg) {
    const std::string path = string_arg(path_arg, "path", true);
    AovSet aovs;
    {
        py::gil_scoped_release release;
        aovs = read_every_part(path);
    }
    return to_python(aovs);
}

void write(const py::object &path_arg, const py::object &aovs, const py::object &compression,
           const py::object &half) {
    const std::string path = string_arg(path_arg, "path", true);
    require_exr_path(path);
    if (!py::isinstance<py::bool_>(half)) throw Error("half: expected a bool, got " + type_name_of(half));
    io::WriteOptions options;
    options.compression = string_arg(compression, "compression");
    options.half_colour = half.cast<bool>();
    const AovSet set = with_context(path, [&] { return from_python(aovs_arg(aovs, "aovs")); });
    py::gil_scoped_release release;
    io::write_aovs(set, path, options);
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
        if (metric->needs == io::CompareMetric::Needs::Temporal)
            throw Error("metrics: '" + key +
                        "' is a sequence's, between consecutive frames (aaf compare "
                        "shot.####.exr ref.####.exr); compare() measures one pair");
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

void def_errors(py::module_ &m) {
    // Translators are tried newest first: the subclasses after their base Error.
    const py::exception<Error> &error = py::register_exception<Error>(m, "Error");
    py::register_exception<InputError>(m, "InputError", error.ptr());
    py::register_exception<Cancelled>(m, "Cancelled", error.ptr());
}

void def_aovs_class(py::module_ &m) {
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
}

void def_file_io(py::module_ &m) {
    m.def("read", &read, py::arg("path"),
          "Reads every channel of every part of an AOV EXR (path: str or os.PathLike) as float32 arrays, "
          "with the first part's header attributes; the parts must share one resolution. Raises "
          "aaf.InputError '<path>: <problem>', e.g. for a file that is not OpenEXR.");
    m.def("write", &write, py::arg("path"), py::arg("aovs"), py::arg("compression") = "zip",
          py::arg("half") = false,
          "Writes `aovs` as an OpenEXR file (float channels; half=True stores colour layers as half), "
          "atomically; a path named .png, .jpg, .tif or another image format is refused. Raises "
          "aaf.InputError '<path>: <problem>', aaf.Error naming a bad argument.");
}

void def_metrics(py::module_ &m) {
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

}  // namespace

}  // namespace aaf::python

PYBIND11_MODULE(aaf, m) {
    m.doc() = "libaaf: image-space reconstruction of ray-traced distribution effects";
    m.attr("__version__") = AAF_VERSION;
    aaf::python::def_errors(m);
    aaf::python::def_aovs_class(m);
    aaf::python::def_file_io(m);
    aaf::python::def_method_info(m);
    aaf::python::def_filtering(m);
    aaf::python::def_metrics(m);
}
