#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/compare_files.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/heatmap.h"
#include "aaf/io/sequence.h"
#include "channel_options.h"
#include "commands.h"
#include "compare_pairs.h"
#include "provenance.h"

namespace aaf::cli {

namespace {

using io::CompareMetric;
using io::ComparePairResult;

const CompareMetric &metric_named(const std::string &key) {
    if (const CompareMetric *metric = io::find_compare_metric(key)) return *metric;
    std::string known;
    for (const CompareMetric &m : io::compare_metrics())
        known += std::string(known.empty() ? "" : ", ") + m.key;
    throw CLI::ValidationError("--metric", "unknown metric '" + key + "' (known: " + known + ")");
}

io::Gate parse_gate(const std::string &spec, bool above) {
    const std::size_t eq = spec.find('=');
    const char *option = above ? "--fail-above" : "--fail-below";
    if (eq == std::string::npos)
        throw CLI::ValidationError(option, "expected METRIC=VALUE, got '" + spec + "'");
    try {
        return {&metric_named(spec.substr(0, eq)), std::stod(spec.substr(eq + 1)), above};
    } catch (const std::invalid_argument &) {
        throw CLI::ValidationError(option, "'" + spec.substr(eq + 1) + "' is not a number");
    }
}

/// JSON has no infinity or NaN: they are written as null.
nlohmann::json number(double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

std::string format(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

using Metrics = std::vector<const CompareMetric *>;

/// `field` as an RFC 4180 CSV field: quoted, its quotes doubled, when it holds
/// a comma, a quote or a line break (a file name may).
std::string csv_field(const std::string &field) {
    if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
    std::string quoted = "\"";
    for (char c : field) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

/// One CSV row per pair, written to a temporary and renamed onto `path`.
void write_csv(const std::string &path, const Metrics &chosen, const std::vector<ComparePairResult> &results,
               double peak) {
    const std::string temporary = io::temporary_path_for(path);
    {
        std::ofstream csv(temporary);
        csv << "label,test,reference";
        for (const CompareMetric *m : chosen) csv << ',' << m->key;
        csv << ",pixels,nonfinite_pixels,spp,psnr_peak\n";
        for (std::size_t i = 0; i < results.size(); ++i) {
            const ComparePairResult &r = results[i];
            csv << csv_field(r.pair.label) << ',' << csv_field(r.pair.test) << ','
                << csv_field(r.pair.reference);
            for (const CompareMetric *m : chosen)
                csv << ',' << (io::defined_for_pair(*m, i) ? format(r.metrics.*(m->value)) : "");
            csv << ',' << r.metrics.pixels << ',' << r.metrics.nonfinite_pixels << ','
                << (std::isfinite(r.spp) ? format(r.spp) : "") << ',' << format(peak) << '\n';
        }
        if (!csv) throw Error(path + ": cannot write");
    }
    io::commit_temporary(temporary, path);
}

/// A pair's metrics; one undefined for it (the first frame's temporal error) is null.
nlohmann::json metrics_json(const Metrics &chosen, const ComparePairResult &r, std::size_t index) {
    nlohmann::json object;
    object["spp"] = number(r.spp);
    for (const CompareMetric *m : chosen)
        object[m->key] = io::defined_for_pair(*m, index) ? number(r.metrics.*(m->value)) : nlohmann::json();
    object["pixels"] = r.metrics.pixels;
    object["nonfinite_pixels"] = r.metrics.nonfinite_pixels;
    return object;
}

/// One object for a single pair; the pairs, a summary per metric and the
/// unmatched files for a batch. Both state the PSNR's peak.
void print_json(const Metrics &chosen, const std::vector<ComparePairResult> &results, bool batch, double peak,
                const std::vector<std::string> &unmatched) {
    nlohmann::json out;
    if (!batch) {
        out = metrics_json(chosen, results[0], 0);
        out["test"] = results[0].pair.test;
        out["reference"] = results[0].pair.reference;
        out["channels"] = results[0].channels;
    } else {
        out["unmatched"] = unmatched;
        for (std::size_t i = 0; i < results.size(); ++i) {
            const ComparePairResult &r = results[i];
            nlohmann::json pair = metrics_json(chosen, r, i);
            pair["label"] = r.pair.label;
            pair["test"] = r.pair.test;
            pair["reference"] = r.pair.reference;
            out["pairs"].push_back(pair);
        }
        for (const CompareMetric *m : chosen) {
            const io::MetricSummary summary = io::summarise(results, *m);
            out["summary"][m->key] = {{"mean", number(summary.mean)},
                                      {"median", number(summary.median)},
                                      {"worst", number(summary.worst)},
                                      {"worst_label", results[summary.worst_index].pair.label}};
        }
    }
    out["psnr_peak"] = peak;
    std::cout << out.dump() << "\n";
}

bool has_psnr(const Metrics &chosen) {
    for (const CompareMetric *m : chosen)
        if (std::string(m->key) == "psnr") return true;
    return false;
}

/// The single pair's metrics on one line.
void print_line(const Metrics &chosen, const ErrorMetrics &em, double peak) {
    std::string line;
    for (const CompareMetric *m : chosen)
        line += std::string(line.empty() ? "" : "  ") + m->label + " " +
                (std::string(m->key) == "psnr" ? format(em.psnr) + " dB (peak " + format(peak) + ")"
                                               : format(em.*(m->value)));
    if (em.nonfinite_pixels) line += "  (" + std::to_string(em.nonfinite_pixels) + " NaN/Inf pixels skipped)";
    std::cout << line << "\n";
}

/// A row per pair, then the mean, median and worst of each metric.
void print_table(const Metrics &chosen, const std::vector<ComparePairResult> &results, double peak) {
    std::printf("%-24s", "pair");
    for (const CompareMetric *m : chosen) std::printf(" %12s", m->label);
    std::printf(" %10s\n", "NaN/Inf");
    for (std::size_t i = 0; i < results.size(); ++i) {
        const ComparePairResult &r = results[i];
        std::printf("%-24s", r.pair.label.c_str());
        for (const CompareMetric *m : chosen)
            std::printf(" %12s", io::defined_for_pair(*m, i) ? format(r.metrics.*(m->value)).c_str() : "-");
        std::printf(" %10zu\n", r.metrics.nonfinite_pixels);
    }
    std::vector<io::MetricSummary> summaries;
    for (const CompareMetric *m : chosen) summaries.push_back(io::summarise(results, *m));
    using Row = std::pair<const char *, double io::MetricSummary::*>;
    for (const Row &row : {Row{"mean", &io::MetricSummary::mean}, Row{"median", &io::MetricSummary::median},
                           Row{"worst", &io::MetricSummary::worst}}) {
        std::printf("%-24s", row.first);
        for (const io::MetricSummary &summary : summaries)
            std::printf(" %12s", format(summary.*row.second).c_str());
        std::printf("\n");
    }
    // Each metric's worst pair may differ: name it under the worst value.
    std::printf("%-24s", "worst pair");
    for (const io::MetricSummary &summary : summaries)
        std::printf(" %12s", results[summary.worst_index].pair.label.c_str());
    std::printf("\n");
    if (has_psnr(chosen)) std::printf("PSNR in dB, peak %s (--peak)\n", format(peak).c_str());
}

/// Lists the batch's files without a namesake on stderr; with --fail-unmatched they fail the check.
void report_unmatched(const std::vector<std::string> &unmatched, bool fail) {
    for (const std::string &path : unmatched)
        std::fprintf(stderr, "aaf: compare: %s: %s, not compared\n", fail ? "error" : "warning",
                     (path + ": no file of that name on the other side").c_str());
}

/// "[3/10] frame: RMSE 0.01 (2.1 s, about 4.9 s left)" on stderr after each pair of a batch.
void print_progress(std::size_t index, std::size_t total, const ComparePairResult &result,
                    const CompareMetric &metric, double elapsed_s) {
    const double left_s = elapsed_s / double(index + 1) * double(total - index - 1);
    std::fprintf(stderr, "[%zu/%zu] %s: %s %s (%.1f s, about %.1f s left)\n", index + 1, total,
                 result.pair.label.c_str(), metric.label, format(result.metrics.*(metric.value)).c_str(),
                 elapsed_s, left_s);
}

/// Names each pair and gate that failed on stderr; throws CheckFailed when any did.
void check_gates(const std::vector<ComparePairResult> &results, const std::vector<io::Gate> &gates) {
    const std::vector<io::GateFailure> failures = io::failed_gates(results, gates);
    for (const io::GateFailure &f : failures)
        std::fprintf(stderr, "aaf: compare: %s: %s %s is %s %s\n", results[f.pair_index].pair.test.c_str(),
                     f.gate.metric->key, format(f.value).c_str(), f.gate.above ? "above" : "below",
                     format(f.gate.limit).c_str());
    if (!failures.empty()) throw CheckFailed{};
}

/// The command line of `aaf compare`.
struct Options {
    std::string test, reference, frames, layer, mask_path, mask_channel, csv, heatmap;
    std::vector<std::string> channels{"R", "G", "B"};
    std::vector<std::string> metric_keys{"rmse", "mse", "psnr"};
    std::vector<int> crop;
    std::vector<std::string> fail_above, fail_below;
    const CLI::Option *frames_option = nullptr;    ///< tells `--frames ''` from no --frames
    const CLI::Option *channels_option = nullptr;  ///< tells --channels R,G,B from none
    const CLI::Option *metric_option = nullptr;    ///< tells --metric rmse,mse,psnr from none
    double peak = 1.0;
    float ppd = 67.0206f;
    bool json = false;
    bool timing = false;
    bool fail_unmatched = false;
    bool progress = false;
};

/// What the library is to measure and write for these options.
io::CompareFilesOptions library_options(const Options &o, const Metrics &chosen,
                                        const std::vector<io::Gate> &gates) {
    io::CompareFilesOptions compare;
    compare.channels = o.channels;
    compare.layer = o.layer;
    compare.metrics = chosen;
    for (const io::Gate &gate : gates) compare.metrics.push_back(gate.metric);
    compare.psnr_peak = o.peak;
    compare.flip_pixels_per_degree = o.ppd;
    if (!o.crop.empty()) {
        // Where it lies is the images' business (exit 3 when outside); a size is not.
        if (o.crop[2] <= 0 || o.crop[3] <= 0)
            throw UsageError("--crop: width and height must be positive, got " + std::to_string(o.crop[2]) +
                             "x" + std::to_string(o.crop[3]));
        compare.crop = PixelRect{o.crop[0], o.crop[1], o.crop[2], o.crop[3]};
    }
    if (!o.mask_path.empty()) compare.mask = io::read_compare_mask(o.mask_path, o.mask_channel);
    if (!o.csv.empty()) compare.report_paths.push_back(o.csv);
    compare.heatmap = o.heatmap;
    return compare;
}

/// The channels measured when none are given: what the method that wrote
/// `test` estimates (MethodInfo::compared) against the role holding the same
/// quantity in the reference; R,G,B for a beauty, a render, or another file.
std::vector<std::string> channels_by_role(const std::string &test) {
    const std::string name = io::read_string_attribute(test, provenance_attr::kMethod);
    const Method *method = nullptr;
    for (const Method *candidate : methods())
        if (candidate->info().name == name) method = candidate;
    if (!method) return {"R", "G", "B"};
    const auto &[estimate, reference] = method->info().compared;
    const std::vector<std::string> &tested = role_info(estimate).channels;
    const std::vector<std::string> &against = role_info(reference).channels;
    std::vector<std::string> channels;
    for (std::size_t c = 0; c < tested.size() && c < against.size(); ++c)
        channels.push_back(tested[c] == against[c] ? tested[c] : tested[c] + "=" + against[c]);
    return channels;
}

/// Measures, prints the results (text, JSON, CSV) and applies the gates.
void run_compare(const Options &o) {
    std::vector<std::string> keys = o.metric_keys;
    // A sequence's flicker beside its per-frame error, unless metrics were chosen.
    if (o.metric_option->count() == 0 && io::is_sequence_pattern(o.test)) keys.push_back("temporal_rmse");
    Metrics chosen;
    for (const std::string &key : keys) chosen.push_back(&metric_named(key));
    std::vector<io::Gate> gates;
    for (const std::string &spec : o.fail_above) gates.push_back(parse_gate(spec, true));
    for (const std::string &spec : o.fail_below) gates.push_back(parse_gate(spec, false));
    io::CompareFilesOptions compare = library_options(o, chosen, gates);
    // One file: a filter's output is compared by what its method estimates.
    if (o.channels_option->count() == 0 && o.layer.empty() && !is_batch_input(o.test))
        compare.channels = channels_by_role(o.test);

    std::vector<std::string> unmatched;
    const io::ImagePairs pairs =
        compare_pairs(o.test, o.reference, given(o.frames_option, o.frames), &unmatched);
    report_unmatched(unmatched, o.fail_unmatched);
    for (const CompareMetric *m : compare.metrics)
        if (m->needs == CompareMetric::Needs::Temporal && !io::is_sequence_pattern(o.test))
            throw UsageError(
                std::string(m->key) +
                ": the temporal error is a sequence's (shot.####.exr), between consecutive frames");
    // A sequence or folder is a batch even when it matches one pair: its output keeps the batch shape.
    const bool batch = is_batch_input(o.test);
    if (!o.heatmap.empty() && pairs.size() != 1)
        throw UsageError(o.heatmap + ": --heatmap needs a single pair of images");
    // The PNG's name; its EXR is written beside it.
    if (!o.heatmap.empty()) require_png_name(o.heatmap, "--heatmap");
    const auto start = std::chrono::steady_clock::now();
    if (o.progress && batch)
        compare.on_pair = [&](std::size_t index, const ComparePairResult &r) {
            const double elapsed_s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            print_progress(index, pairs.size(), r, chosen.empty() ? io::compare_metrics()[0] : *chosen[0],
                           elapsed_s);
        };
    const io::CompareFilesResult result = io::compare_files(pairs, compare);
    if (!o.heatmap.empty())
        std::fprintf(stderr, "heatmap %s: colour bar 0 to %s (99th percentile)\n", o.heatmap.c_str(),
                     format(result.heatmap_scale).c_str());
    if (o.timing)
        std::fprintf(stderr, "timing: read %.3f s, metrics %.3f s over %zu pairs\n", result.read_seconds,
                     result.measure_seconds, result.pairs.size());
    if (!o.csv.empty()) write_csv(o.csv, chosen, result.pairs, o.peak);
    if (o.json)
        print_json(chosen, result.pairs, batch, o.peak, unmatched);
    else if (!batch)
        print_line(chosen, result.pairs[0].metrics, o.peak);
    else
        print_table(chosen, result.pairs, o.peak);
    if (o.fail_unmatched && !unmatched.empty()) {
        std::fprintf(stderr, "aaf: compare: %zu unmatched files (--fail-unmatched)\n", unmatched.size());
        check_gates(result.pairs, gates);
        throw CheckFailed{};
    }
    check_gates(result.pairs, gates);
}

}  // namespace

void add_compare_command(CLI::App &app) {
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand(
        "compare", "Error of images against references: one pair, two sequences or two folders");
    cmd->add_option("test", options->test, "Image, sequence pattern (shot.####.exr) or folder")->required();
    cmd->add_option("reference", options->reference, "Reference image, pattern or folder")->required();
    options->frames_option = cmd->add_option(
        "--frames", options->frames, "Frame range of the sequences: 1-100, 1-100x2, 1-100:2, 1,5,7-9");
    options->metric_option =
        cmd->add_option(
               "--metric", options->metric_keys,
               "Metrics: rmse, mse, mae, relmse, psnr, ssim, flip (mean), flip_median (weighted median), "
               "temporal_rmse (a sequence's flicker: RMSE of the frame-to-frame change of test - "
               "reference; added to the default for sequences)")
            ->delimiter(',')
            ->capture_default_str();
    options->channels_option =
        cmd->add_option(
               "--channels", options->channels,
               "Channels to compare: NAME (in both) or TEST=REFERENCE (aaf.V=shadow.V); R,G,B and other "
               "contract names find a renderer's channels of the role (ViewLayer.Combined.R)")
            ->delimiter(',')
            ->capture_default_str();
    cmd->add_option("--layer", options->layer,
                    "Compare every channel of this layer (e.g. aaf); refused when they mix units "
                    "(shadow.V with shadow.d1)");
    cmd->add_option("--crop", options->crop, "Only the rectangle X,Y,WIDTH,HEIGHT (pixels)")
        ->delimiter(',')
        ->expected(4);
    cmd->add_option("--mask", options->mask_path, "Only pixels where this image is non-zero");
    cmd->add_option("--mask-channel", options->mask_channel, "Channel of the mask (default: its first)");
    cmd->add_option("--peak", options->peak, "PSNR peak value (linear HDR images have no white)")
        ->check(finite_number(0))
        ->capture_default_str();
    cmd->add_option("--ppd", options->ppd,
                    "FLIP pixels per degree (default: 0.7 m from a 0.7 m wide 4K display)")
        ->check(finite_number(0))
        ->capture_default_str();
    cmd->add_option("--fail-above", options->fail_above, "Exit 4 when METRIC=VALUE is exceeded by any pair");
    cmd->add_option("--fail-below", options->fail_below, "Exit 4 when any pair's METRIC falls below VALUE");
    cmd->add_flag("--json", options->json,
                  "Print JSON: one object for two files; pairs and summary for sequences or folders");
    cmd->add_option("--csv", options->csv, "Also write one CSV row per pair to this file");
    cmd->add_flag("--timing", options->timing, "Print the seconds spent reading and measuring to stderr");
    cmd->add_flag("--fail-unmatched", options->fail_unmatched,
                  "Exit 4 when a folder holds files without a namesake in the other (listed either way)");
    cmd->add_flag("--progress", options->progress,
                  "Batch: a line per pair on stderr with the first metric and the time left");
    cmd->add_option("--heatmap", options->heatmap,
                    "Per-pixel error as a false-colour PNG with a colour bar, and as an EXR beside it "
                    "(X.png and X.exr); covers the --crop region, --mask's masked-out pixels black");
    cmd->callback([options, cmd] {
        bool flip = false;
        for (const std::string &key : options->metric_keys) flip = flip || key.rfind("flip", 0) == 0;
        for (const auto *gates : {&options->fail_above, &options->fail_below})
            for (const std::string &gate : *gates) flip = flip || gate.rfind("flip", 0) == 0;
        if (cmd->count("--ppd") > 0 && !flip)
            std::fprintf(stderr, "aaf: warning: --ppd has no effect without a flip metric\n");
        if (cmd->count("--mask-channel") > 0 && options->mask_path.empty())
            std::fprintf(stderr, "aaf: warning: --mask-channel has no effect without --mask\n");
        if (cmd->count("--progress") > 0 && !is_batch_input(options->test))
            std::fprintf(stderr, "aaf: warning: --progress has no effect on a single pair\n");
        run_compare(*options);
    });
}

}  // namespace aaf::cli
