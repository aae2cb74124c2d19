#include "aaf/io/compare_files.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <utility>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/kernels/sample_statistics.h"
#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/channel_lookup.h"
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

/// The role whose channels (as `resolved` names them in an image) include
/// `channel`, or nullptr when no role claims it.
const RoleInfo *role_of(const std::string &channel, const ChannelMap &resolved) {
    for (const RoleInfo &info : role_table()) {
        const std::vector<std::string> &names = resolved.channels(info.role);
        if (std::find(names.begin(), names.end(), channel) != names.end()) return &info;
    }
    return nullptr;
}

/// The channels of `options.layer` in `test`; refuses a layer whose
/// channels hold quantities of different units (AOV contract roles), such
/// as shadow.V (visibility) beside shadow.d1 (metres), whose average would
/// mean nothing.
std::vector<std::string> layer_channels(const ImagePair &pair, const AovSet &test,
                                        const CompareFilesOptions &options) {
    std::vector<std::string> channels;
    for (const std::string &name : test.channel_names())
        if (name.rfind(options.layer + ".", 0) == 0) channels.push_back(name);
    if (channels.empty()) throw InputError(pair.test + ": no channels in layer '" + options.layer + "'");
    const ChannelMap resolved = ChannelMap().resolved(test);
    std::vector<std::pair<std::string, std::string>> units;  // (units, channels of them)
    for (const std::string &name : channels) {
        const RoleInfo *role = role_of(name, resolved);
        if (!role) continue;
        // "metres, 0 = no occluder" is metres: the unit is what precedes a comma.
        const std::string unit = std::string(role->units).substr(0, std::string(role->units).find(','));
        auto group =
            std::find_if(units.begin(), units.end(), [&unit](const auto &u) { return u.first == unit; });
        if (group == units.end())
            units.emplace_back(unit, name);
        else
            group->second += ", " + name;
    }
    if (units.size() > 1) {
        std::string kinds, suggestion = units.front().second.substr(0, units.front().second.find(','));
        for (const auto &u : units) kinds += (kinds.empty() ? "" : "; ") + u.second + " (" + u.first + ")";
        for (const std::string &name : channels)  // the visibility, what a shadow filter is scored on
            if (const RoleInfo *role = role_of(name, resolved))
                if (role->role == Role::Visibility || role->role == Role::FilteredVisibility)
                    suggestion = name;
        throw InputError(pair.test + ": layer '" + options.layer + "' mixes quantities of different units: " +
                         kinds + "; compare one kind with --channels, e.g. --channels " + suggestion);
    }
    return channels;
}

/// What one pair compares: each requested channel as the test image holds
/// it and the reference channel it is measured against.
struct ChannelPairs {
    std::vector<std::string> test, reference;
    std::vector<std::string> labels;  ///< "name", or "test=reference" where they differ
};

/// `options.layer`'s channels, else `options.channels`, each "name" or
/// "test=reference" and resolved in its image through the role table.
ChannelPairs channels_to_compare(const ImagePair &pair, const AovSet &test, const AovSet &reference,
                                 const CompareFilesOptions &options) {
    ChannelPairs channels;
    const std::vector<std::string> requested =
        options.layer.empty() ? options.channels : layer_channels(pair, test, options);
    for (const std::string &spec : requested) {
        const std::size_t eq = spec.find('=');
        const std::string test_name = resolve_channel(spec.substr(0, eq), test);
        const std::string reference_name =
            resolve_channel(eq == std::string::npos ? spec : spec.substr(eq + 1), reference);
        channels.test.push_back(test_name);
        channels.reference.push_back(reference_name);
        channels.labels.push_back(test_name == reference_name ? test_name : test_name + "=" + reference_name);
    }
    return channels;
}

/// compare_images()'s options for one pair of images.
CompareOptions pair_options(const ImagePair &pair, const AovSet &test,
                            const std::vector<std::string> &channels, const CompareFilesOptions &options) {
    CompareOptions compare;
    compare.channels = channels;
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

/// A pair ready for compare_images(): the reference's compared channels
/// under the test image's names (a copy only where a name differs).
struct PreparedPair {
    CompareOptions compare;
    std::vector<std::string> labels;
    AovSet renamed_reference;
    bool renamed = false;
};

PreparedPair prepare_pair(const ImagePair &pair, const AovSet &test, const AovSet &reference,
                          const CompareFilesOptions &options) {
    const ChannelPairs channels = channels_to_compare(pair, test, reference, options);
    PreparedPair prepared{pair_options(pair, test, channels.test, options), channels.labels, {}, false};
    if (channels.test == channels.reference) return prepared;
    prepared.renamed = true;
    prepared.renamed_reference = AovSet(reference.width(), reference.height());
    for (std::size_t c = 0; c < channels.test.size(); ++c) {
        if (prepared.renamed_reference.has_channel(channels.test[c])) continue;  // listed twice
        if (!reference.has_channel(channels.reference[c]))
            throw InputError(pair.reference + ": no channel '" + channels.reference[c] +
                             "' to compare with " + channels.test[c]);
        const ConstPlaneView from = reference.channel(channels.reference[c]);
        PlaneView to = prepared.renamed_reference.add_channel(channels.test[c]);
        for (int y = 0; y < reference.height(); ++y)
            for (int x = 0; x < reference.width(); ++x) to(x, y) = from(x, y);
    }
    return prepared;
}

/// Reads, measures and (with a heatmap) draws one pair, adding to the timings.
ComparePairResult compare_pair(const ImagePair &pair, const CompareFilesOptions &options,
                               CompareFilesResult &totals, ErrorImage *error) {
    const auto read_start = Clock::now();
    const AovSet test = read_aovs(pair.test), reference = read_aovs(pair.reference);
    totals.read_seconds += seconds_since(read_start);
    const auto measure_start = Clock::now();
    const PreparedPair prepared = prepare_pair(pair, test, reference, options);
    const AovSet &measured = prepared.renamed ? prepared.renamed_reference : reference;
    return with_context(pair.test + " vs " + pair.reference, [&] {
        ComparePairResult result{pair, prepared.labels,
                                 compare_images(test, measured, prepared.compare, error), mean_spp_of(test)};
        totals.measure_seconds += seconds_since(measure_start);
        if (!options.heatmap.empty())
            totals.heatmap_scale = write_error_heatmap(test, measured, prepared.compare, options.heatmap);
        return result;
    });
}

}  // namespace

ComparePairResult compare_aov_sets(const ImagePair &pair, const AovSet &test, const AovSet &reference,
                                   const CompareFilesOptions &options) {
    const PreparedPair prepared = prepare_pair(pair, test, reference, options);
    const AovSet &measured = prepared.renamed ? prepared.renamed_reference : reference;
    return with_context(pair.test + " vs " + pair.reference, [&] {
        return ComparePairResult{pair, prepared.labels, compare_images(test, measured, prepared.compare),
                                 mean_spp_of(test)};
    });
}

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
        {"temporal_rmse", "temporal", false, &ErrorMetrics::temporal_rmse, Needs::Temporal},
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
    const bool temporal = needs(options, CompareMetric::Needs::Temporal);
    ErrorImage previous, current;  // the last pair's error and this one's
    // Outputs are written after every pair is read: checking each pair just
    // before reading it refuses an overwrite before anything is written.
    pairs.for_each([&](const ImagePair &pair) {
        check_pair_not_output(pair, outputs);
        ComparePairResult measured = compare_pair(pair, options, result, temporal ? &current : nullptr);
        if (temporal && !result.pairs.empty())
            measured.metrics.temporal_rmse =
                with_context(pair.test + " after " + result.pairs.back().pair.test,
                             [&] { return temporal_rmse(previous, current); });
        std::swap(previous, current);
        result.pairs.push_back(std::move(measured));
        if (options.on_pair) options.on_pair(result.pairs.size() - 1, result.pairs.back());
    });
    return result;
}

bool defined_for_pair(const CompareMetric &metric, std::size_t pair_index) {
    return metric.needs != CompareMetric::Needs::Temporal || pair_index > 0;
}

MetricSummary summarise(const std::vector<ComparePairResult> &results, const CompareMetric &metric) {
    const std::size_t first = defined_for_pair(metric, 0) ? 0 : 1;
    if (results.size() <= first) throw Error(std::string("no pairs to summarise ") + metric.key + " over");
    MetricSummary summary;
    summary.worst_index = first;
    std::vector<double> values;
    for (std::size_t i = first; i < results.size(); ++i) {
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
            if (!defined_for_pair(*gate.metric, i)) continue;
            const double value = results[i].metrics.*(gate.metric->value);
            if (gate.above ? !(value <= gate.limit) : !(value >= gate.limit))
                failures.push_back({i, gate, value});
        }
    return failures;
}

}  // namespace aaf::io
