#include "aaf/io/compare_files.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <utility>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/core/sample_statistics.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/heatmap.h"

namespace aaf::io {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool needs(const CompareFilesOptions &options, CompareMetric::Needs what) {
    return std::any_of(options.metrics.begin(), options.metrics.end(),
                       [what](const CompareMetric *m) { return m->needs == what; });
}

/// Mean spp of an image that carries the contract's spp and object-id AOVs.
double mean_spp_of(const AovSet &image) {
    const ChannelMap channels;
    const std::string &spp = channels.channel(Role::SamplesPerPixel), &id = channels.channel(Role::ObjectId);
    if (!image.has_channel(spp) || !image.has_channel(id)) return std::nan("");
    return mean_spp_over_shaded(image.channel(spp), image.channel(id));
}

/// The files compare_files() writes (reports, the heatmap's two files);
/// refuses a heatmap it cannot write.
std::vector<std::string> checked_outputs(const ImagePairs &pairs, const CompareFilesOptions &options) {
    std::vector<std::string> outputs = options.report_paths;
    if (!options.heatmap.empty()) {
        if (pairs.size() != 1) throw Error(options.heatmap + ": a heatmap needs a single pair of images");
        if (heatmap_exr_path(options.heatmap) == options.heatmap)
            throw Error(options.heatmap + ": ends in .exr: name the PNG, the EXR is written beside it");
        outputs.push_back(options.heatmap);
        outputs.push_back(heatmap_exr_path(options.heatmap));
    }
    for (const std::string &output : outputs)
        if (options.mask) check_not_same_file(options.mask->path, output);
    return outputs;
}

/// Refuses a pair that one of `outputs` would replace.
void check_pair_not_output(const ImagePair &pair, const std::vector<std::string> &outputs) {
    for (const std::string &output : outputs) {
        check_not_same_file(pair.test, output);
        check_not_same_file(pair.reference, output);
    }
}

/// The channels to compare in `test`: `options.layer`'s, else `options.channels`.
std::vector<std::string> channels_to_compare(const ImagePair &pair, const AovSet &test,
                                             const CompareFilesOptions &options) {
    if (options.layer.empty()) return options.channels;
    std::vector<std::string> channels;
    for (const std::string &name : test.channel_names())
        if (name.rfind(options.layer + ".", 0) == 0) channels.push_back(name);
    if (channels.empty()) throw InputError(pair.test + ": no channels in layer '" + options.layer + "'");
    return channels;
}

/// compare_images()'s options for one pair of images.
CompareOptions pair_options(const ImagePair &pair, const AovSet &test, const CompareFilesOptions &options) {
    CompareOptions compare;
    compare.channels = channels_to_compare(pair, test, options);
    compare.crop = options.crop;
    compare.psnr_peak = options.psnr_peak;
    compare.compute_ssim = needs(options, CompareMetric::Needs::Ssim);
    // HDR-FLIP for linear EXR data, LDR-FLIP for display-encoded files (PNG, JPEG, ...).
    const std::string extension = std::filesystem::path(pair.reference).extension().string();
    const bool linear = extension == ".exr" || extension == ".EXR";
    compare.flip = !needs(options, CompareMetric::Needs::Flip)
                       ? CompareOptions::Flip::Off
                       : (linear ? CompareOptions::Flip::Hdr : CompareOptions::Flip::Ldr);
    compare.flip_pixels_per_degree = options.flip_pixels_per_degree;
    if (options.mask) {
        compare.mask = options.mask->image.channel(options.mask->channel);
        if (compare.mask.width != test.width() || compare.mask.height != test.height())
            throw InputError(options.mask->path + ": the mask is " + std::to_string(compare.mask.width) +
                             "x" + std::to_string(compare.mask.height) + ", " + pair.test + " is " +
                             std::to_string(test.width()) + "x" + std::to_string(test.height()));
    }
    return compare;
}

/// Reads, measures and (with a heatmap) draws one pair, adding to the timings.
ComparePairResult compare_pair(const ImagePair &pair, const CompareFilesOptions &options,
                               CompareFilesResult &totals) {
    const auto read_start = Clock::now();
    const AovSet test = read_aovs(pair.test), reference = read_aovs(pair.reference);
    totals.read_seconds += seconds_since(read_start);
    const auto measure_start = Clock::now();
    const CompareOptions compare = pair_options(pair, test, options);
    return with_context(pair.test + " vs " + pair.reference, [&] {
        ComparePairResult result{pair, compare.channels, compare_images(test, reference, compare),
                                 mean_spp_of(test)};
        totals.measure_seconds += seconds_since(measure_start);
        if (!options.heatmap.empty())
            totals.heatmap_scale = write_error_heatmap(test, reference, compare, options.heatmap);
        return result;
    });
}

}  // namespace

const std::vector<CompareMetric> &compare_metrics() {
    using Needs = CompareMetric::Needs;
    static const std::vector<CompareMetric> table = {
        {"rmse", "RMSE", false, &ErrorMetrics::rmse, Needs::Sums},
        {"mse", "MSE", false, &ErrorMetrics::mse, Needs::Sums},
        {"mae", "MAE", false, &ErrorMetrics::mae, Needs::Sums},
        {"relmse", "relMSE", false, &ErrorMetrics::relmse, Needs::Sums},
        {"psnr", "PSNR", true, &ErrorMetrics::psnr, Needs::Sums},
        {"ssim", "SSIM", true, &ErrorMetrics::ssim, Needs::Ssim},
        {"flip", "FLIP", false, &ErrorMetrics::flip_mean, Needs::Flip},
        {"flip_median", "FLIP-wmedian", false, &ErrorMetrics::flip_weighted_median, Needs::Flip},
    };
    return table;
}

const CompareMetric *find_compare_metric(const std::string &key) {
    for (const CompareMetric &m : compare_metrics())
        if (key == m.key) return &m;
    return nullptr;
}

CompareMask read_compare_mask(const std::string &path, const std::string &channel) {
    CompareMask mask{path, read_aovs(path), channel};
    if (mask.channel.empty()) mask.channel = mask.image.channel_names().front();
    if (!mask.image.has_channel(mask.channel))
        throw InputError(path + ": no channel '" + mask.channel + "' for the mask");
    return mask;
}

ImagePairs::ImagePairs(std::vector<ImagePair> pairs) : list_(std::move(pairs)), count_(list_.size()) {}

ImagePairs::ImagePairs(std::size_t count, std::function<void(const Visit &)> produce)
    : count_(count), produce_(std::move(produce)) {}

void ImagePairs::for_each(const Visit &visit) const {
    for (const ImagePair &pair : list_) visit(pair);
    if (produce_) produce_(visit);
}

CompareFilesResult compare_files(const ImagePairs &pairs, const CompareFilesOptions &options) {
    const std::vector<std::string> outputs = checked_outputs(pairs, options);
    CompareFilesResult result;
    // Outputs are written after every pair is read: checking each pair just
    // before reading it refuses an overwrite before anything is written.
    pairs.for_each([&](const ImagePair &pair) {
        check_pair_not_output(pair, outputs);
        result.pairs.push_back(compare_pair(pair, options, result));
    });
    return result;
}

MetricSummary summarise(const std::vector<ComparePairResult> &results, const CompareMetric &metric) {
    if (results.empty()) throw Error(std::string("no pairs to summarise ") + metric.key + " over");
    MetricSummary summary;
    std::vector<double> values;
    for (std::size_t i = 0; i < results.size(); ++i) {
        const double v = results[i].metrics.*(metric.value);
        const double w = results[summary.worst_index].metrics.*(metric.value);
        if (metric.higher_is_better ? v < w : v > w) summary.worst_index = i;
        values.push_back(v);
    }
    for (double v : values) summary.mean += v / double(values.size());
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    summary.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    summary.worst = results[summary.worst_index].metrics.*(metric.value);
    return summary;
}

std::vector<GateFailure> failed_gates(const std::vector<ComparePairResult> &results,
                                      const std::vector<Gate> &gates) {
    std::vector<GateFailure> failures;
    for (std::size_t i = 0; i < results.size(); ++i)
        for (const Gate &gate : gates) {
            const double value = results[i].metrics.*(gate.metric->value);
            if (gate.above ? !(value <= gate.limit) : !(value >= gate.limit))
                failures.push_back({i, gate, value});
        }
    return failures;
}

}  // namespace aaf::io
