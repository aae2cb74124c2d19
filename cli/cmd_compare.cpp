#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/core/error_metrics.h"
#include "aaf/core/sample_statistics.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/heatmap.h"
#include "commands.h"
#include "compare_pairs.h"

namespace aaf::cli {

namespace {

/// A metric `aaf compare` can report.
struct Metric {
    const char *key;    ///< --metric spelling, JSON and CSV key
    const char *label;  ///< table heading
    bool higher_is_better;
    double ErrorMetrics::*value;
};

const std::vector<Metric> &metrics() {
    static const std::vector<Metric> table = {
        {"rmse", "RMSE", false, &ErrorMetrics::rmse},
        {"mse", "MSE", false, &ErrorMetrics::mse},
        {"mae", "MAE", false, &ErrorMetrics::mae},
        {"relmse", "relMSE", false, &ErrorMetrics::relmse},
        {"psnr", "PSNR", true, &ErrorMetrics::psnr},
        {"ssim", "SSIM", true, &ErrorMetrics::ssim},
        {"flip", "FLIP", false, &ErrorMetrics::flip_mean},
        {"flip_median", "FLIP-wmedian", false, &ErrorMetrics::flip_weighted_median},
    };
    return table;
}

const Metric &metric_named(const std::string &key) {
    for (const Metric &m : metrics())
        if (key == m.key) return m;
    std::string known;
    for (const Metric &m : metrics()) known += std::string(known.empty() ? "" : ", ") + m.key;
    throw CLI::ValidationError("--metric", "unknown metric '" + key + "' (known: " + known + ")");
}

/// A threshold of --fail-above / --fail-below.
struct Gate {
    const Metric *metric;
    double limit;
    bool above;  ///< fails when the value is above (else below) the limit
};

Gate parse_gate(const std::string &spec, bool above) {
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

struct Result {
    ImagePair pair;
    ErrorMetrics metrics;
    double spp;  ///< the test image's mean spp over shaded pixels; NaN without those AOVs
};

/// Mean spp of an image that carries the contract's spp and object-id AOVs.
double mean_spp_of(const AovSet &image) {
    const ChannelMap channels;
    const std::string &spp = channels.channel(Role::SamplesPerPixel), &id = channels.channel(Role::ObjectId);
    if (!image.has_channel(spp) || !image.has_channel(id)) return std::nan("");
    return mean_spp_over_shaded(image.channel(spp), image.channel(id));
}

}  // namespace

void add_compare_command(CLI::App &app) {
    struct Options {
        std::string test, reference, frames, layer, mask_path, mask_channel, csv, heatmap;
        std::vector<std::string> channels{"R", "G", "B"};
        std::vector<std::string> metric_keys{"rmse", "mse", "psnr"};
        std::vector<int> crop;
        std::vector<std::string> fail_above, fail_below;
        double peak = 1.0;
        float ppd = 67.0206f;
        bool json = false;
        bool timing = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App *cmd = app.add_subcommand(
        "compare", "Error of images against references: one pair, two sequences or two folders");
    cmd->add_option("test", options->test, "Image, sequence pattern (shot.####.exr) or folder")->required();
    cmd->add_option("reference", options->reference, "Reference image, pattern or folder")->required();
    cmd->add_option("--frames", options->frames,
                    "Frame range of the sequences: 1-100, 1-100x2, 1-100:2, 1,5,7-9");
    cmd->add_option("--metric", options->metric_keys,
                    "Metrics: rmse, mse, mae, relmse, psnr, ssim, flip (mean), flip_median (weighted median)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--channels", options->channels, "Channels to compare")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--layer", options->layer, "Compare every channel of this layer (e.g. shadow)");
    cmd->add_option("--crop", options->crop, "Only the rectangle X,Y,WIDTH,HEIGHT (pixels)")
        ->delimiter(',')
        ->expected(4);
    cmd->add_option("--mask", options->mask_path, "Only pixels where this image is non-zero");
    cmd->add_option("--mask-channel", options->mask_channel, "Channel of the mask (default: its first)");
    cmd->add_option("--peak", options->peak, "PSNR peak value (linear HDR images have no white)")
        ->capture_default_str();
    cmd->add_option("--ppd", options->ppd,
                    "FLIP pixels per degree (default: 0.7 m from a 0.7 m wide 4K display)")
        ->capture_default_str();
    cmd->add_option("--fail-above", options->fail_above, "Exit 4 when METRIC=VALUE is exceeded by any pair");
    cmd->add_option("--fail-below", options->fail_below, "Exit 4 when any pair's METRIC falls below VALUE");
    cmd->add_flag("--json", options->json,
                  "Print JSON: one object for two files; pairs and summary for sequences or folders");
    cmd->add_option("--csv", options->csv, "Also write one CSV row per pair to this file");
    cmd->add_flag("--timing", options->timing, "Print the seconds spent reading and measuring to stderr");
    cmd->add_option("--heatmap", options->heatmap,
                    "Per-pixel error as a false-colour PNG with a colour bar, and as an EXR beside it "
                    "(X.png and X.exr); covers the --crop region, --mask's masked-out pixels black");
    cmd->callback([options] {
        std::vector<const Metric *> chosen;
        for (const std::string &key : options->metric_keys) chosen.push_back(&metric_named(key));
        std::vector<Gate> gates;
        for (const std::string &spec : options->fail_above) gates.push_back(parse_gate(spec, true));
        for (const std::string &spec : options->fail_below) gates.push_back(parse_gate(spec, false));

        CompareOptions compare;
        compare.psnr_peak = options->peak;
        compare.compute_ssim = std::any_of(chosen.begin(), chosen.end(),
                                           [](const Metric *m) { return std::string(m->key) == "ssim"; });
        for (const Gate &gate : gates) compare.compute_ssim |= std::string(gate.metric->key) == "ssim";
        bool want_flip = false;
        for (const Metric *m : chosen) want_flip |= std::string(m->key).rfind("flip", 0) == 0;
        for (const Gate &gate : gates) want_flip |= std::string(gate.metric->key).rfind("flip", 0) == 0;
        compare.flip_pixels_per_degree = options->ppd;
        if (!options->crop.empty())
            compare.crop = PixelRect{options->crop[0], options->crop[1], options->crop[2], options->crop[3]};
        AovSet mask;
        if (!options->mask_path.empty()) {
            mask = io::read_aovs(options->mask_path);
            const std::string channel =
                options->mask_channel.empty() ? mask.channel_names().front() : options->mask_channel;
            if (!mask.has_channel(channel))
                throw InputError(options->mask_path + ": no channel '" + channel + "' for the mask");
            compare.mask = mask.channel(channel);
        }

        const std::vector<ImagePair> pairs =
            compare_pairs(options->test, options->reference, options->frames);
        // A sequence or folder is a batch even when it matches one pair: its output keeps the batch shape.
        const bool batch = is_batch_input(options->test);
        if (!options->heatmap.empty() && pairs.size() != 1)
            throw UsageError(options->heatmap + ": --heatmap needs a single pair of images");
        if (!options->heatmap.empty() && io::heatmap_exr_path(options->heatmap) == options->heatmap)
            throw CLI::ValidationError(
                "--heatmap",
                "'" + options->heatmap + "' ends in .exr: name the PNG, the EXR is written beside it");
        // Nothing compare writes may replace one of its inputs; checked before anything is written.
        std::vector<std::string> outputs;
        if (!options->csv.empty()) outputs.push_back(options->csv);
        if (!options->heatmap.empty()) {
            outputs.push_back(options->heatmap);
            outputs.push_back(io::heatmap_exr_path(options->heatmap));
        }
        for (const std::string &output : outputs) {
            if (!options->mask_path.empty()) io::check_not_same_file(options->mask_path, output);
            for (const ImagePair &pair : pairs) {
                io::check_not_same_file(pair.test, output);
                io::check_not_same_file(pair.reference, output);
            }
        }
        std::vector<Result> results;
        using Clock = std::chrono::steady_clock;
        double read_s = 0, measure_s = 0;
        for (const ImagePair &pair : pairs) {
            const auto read_start = Clock::now();
            const AovSet test = io::read_aovs(pair.test), reference = io::read_aovs(pair.reference);
            const auto measure_start = Clock::now();
            read_s += std::chrono::duration<double>(measure_start - read_start).count();
            compare.channels = options->channels;
            // HDR-FLIP for linear EXR data, LDR-FLIP for display-encoded files (PNG, JPEG, ...).
            const std::string extension = std::filesystem::path(pair.reference).extension().string();
            const bool linear = extension == ".exr" || extension == ".EXR";
            compare.flip = !want_flip ? CompareOptions::Flip::Off
                                      : (linear ? CompareOptions::Flip::Hdr : CompareOptions::Flip::Ldr);
            if (!options->layer.empty()) {
                compare.channels.clear();
                for (const std::string &name : test.channel_names())
                    if (name.rfind(options->layer + ".", 0) == 0) compare.channels.push_back(name);
                if (compare.channels.empty())
                    throw InputError(pair.test + ": no channels in layer '" + options->layer + "'");
            }
            if (compare.mask.valid() &&
                (compare.mask.width != test.width() || compare.mask.height != test.height()))
                throw InputError(options->mask_path + ": the mask is " + std::to_string(compare.mask.width) +
                                 "x" + std::to_string(compare.mask.height) + ", " + pair.test + " is " +
                                 std::to_string(test.width()) + "x" + std::to_string(test.height()));
            with_context(pair.test + " vs " + pair.reference, [&] {
                results.push_back({pair, compare_images(test, reference, compare), mean_spp_of(test)});
                measure_s += std::chrono::duration<double>(Clock::now() - measure_start).count();
                if (!options->heatmap.empty()) {
                    const float scale = io::write_error_heatmap(test, reference, compare, options->heatmap);
                    std::fprintf(stderr, "heatmap %s: colour bar 0 to %s (99th percentile)\n",
                                 options->heatmap.c_str(), format(scale).c_str());
                }
            });
        }

        if (options->timing)
            std::fprintf(stderr, "timing: read %.3f s, metrics %.3f s over %zu pairs\n", read_s, measure_s,
                         results.size());

        if (!options->csv.empty()) {
            const std::string temporary = io::temporary_path_for(options->csv);
            {
                std::ofstream csv(temporary);
                csv << "label,test,reference";
                for (const Metric *m : chosen) csv << ',' << m->key;
                csv << ",pixels,nonfinite_pixels,spp\n";
                for (const Result &r : results) {
                    csv << r.pair.label << ',' << r.pair.test << ',' << r.pair.reference;
                    for (const Metric *m : chosen) csv << ',' << format(r.metrics.*(m->value));
                    csv << ',' << r.metrics.pixels << ',' << r.metrics.nonfinite_pixels << ','
                        << (std::isfinite(r.spp) ? format(r.spp) : "") << '\n';
                }
                if (!csv) throw Error(options->csv + ": cannot write");
            }
            io::commit_temporary(temporary, options->csv);
        }

        // Summary per metric over the pairs: mean, median and the worst pair.
        auto summary_of = [&](const Metric &m) {
            std::vector<double> values;
            const Result *worst = &results.front();
            for (const Result &r : results) {
                values.push_back(r.metrics.*(m.value));
                const double v = r.metrics.*(m.value), w = worst->metrics.*(m.value);
                if (m.higher_is_better ? v < w : v > w) worst = &r;
            }
            double mean = 0;
            for (double v : values) mean += v / double(values.size());
            std::sort(values.begin(), values.end());
            const std::size_t n = values.size();
            const double median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
            return std::make_tuple(mean, median, worst);
        };

        auto metrics_json = [&](const ErrorMetrics &em, double spp) {
            nlohmann::json object;
            object["spp"] = number(spp);
            for (const Metric *m : chosen) object[m->key] = number(em.*(m->value));
            object["pixels"] = em.pixels;
            object["nonfinite_pixels"] = em.nonfinite_pixels;
            return object;
        };
        if (options->json) {
            nlohmann::json out;
            if (!batch) {
                out = metrics_json(results[0].metrics, results[0].spp);
                out["test"] = results[0].pair.test;
                out["reference"] = results[0].pair.reference;
                out["channels"] = compare.channels;
            } else {
                for (const Result &r : results) {
                    nlohmann::json pair = metrics_json(r.metrics, r.spp);
                    pair["label"] = r.pair.label;
                    pair["test"] = r.pair.test;
                    pair["reference"] = r.pair.reference;
                    out["pairs"].push_back(pair);
                }
                for (const Metric *m : chosen) {
                    const auto [mean, median, worst] = summary_of(*m);
                    out["summary"][m->key] = {{"mean", number(mean)},
                                              {"median", number(median)},
                                              {"worst", number(worst->metrics.*(m->value))},
                                              {"worst_label", worst->pair.label}};
                }
            }
            std::cout << out.dump() << "\n";
        } else if (!batch) {
            const ErrorMetrics &em = results[0].metrics;
            std::string line;
            for (const Metric *m : chosen)
                line += std::string(line.empty() ? "" : "  ") + m->label + " " +
                        (std::string(m->key) == "psnr" ? format(em.psnr) + " dB" : format(em.*(m->value)));
            if (em.nonfinite_pixels)
                line += "  (" + std::to_string(em.nonfinite_pixels) + " NaN/Inf pixels skipped)";
            std::cout << line << "\n";
        } else {
            std::printf("%-24s", "pair");
            for (const Metric *m : chosen) std::printf(" %12s", m->label);
            std::printf(" %10s\n", "NaN/Inf");
            for (const Result &r : results) {
                std::printf("%-24s", r.pair.label.c_str());
                for (const Metric *m : chosen) std::printf(" %12s", format(r.metrics.*(m->value)).c_str());
                std::printf(" %10zu\n", r.metrics.nonfinite_pixels);
            }
            for (const char *row : {"mean", "median", "worst"}) {
                std::printf("%-24s", row);
                for (const Metric *m : chosen) {
                    const auto [mean, median, worst] = summary_of(*m);
                    const double v = std::string(row) == "mean"     ? mean
                                     : std::string(row) == "median" ? median
                                                                    : worst->metrics.*(m->value);
                    std::printf(" %12s", format(v).c_str());
                }
                std::printf("\n");
            }
            // Each metric's worst pair may differ: name it under the worst value.
            std::printf("%-24s", "worst pair");
            for (const Metric *m : chosen)
                std::printf(" %12s", std::get<2>(summary_of(*m))->pair.label.c_str());
            std::printf("\n");
        }

        bool failed = false;
        for (const Result &r : results)
            for (const Gate &gate : gates) {
                const double value = r.metrics.*(gate.metric->value);
                if (gate.above ? !(value <= gate.limit) : !(value >= gate.limit)) {
                    std::fprintf(stderr, "aaf: compare: %s: %s %s is %s %s\n", r.pair.test.c_str(),
                                 gate.metric->key, format(value).c_str(), gate.above ? "above" : "below",
                                 format(gate.limit).c_str());
                    failed = true;
                }
            }
        if (failed) throw CheckFailed{};
    });
}

}  // namespace aaf::cli
