#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/core/metrics/error_metrics.h"

namespace aaf::io {

/// One test image and its reference, with a label for reports.
struct ImagePair {
    std::string label;  ///< frame number or file name
    std::string test, reference;
};

/// The pairs to compare, produced one at a time: a sequence of two billion
/// frames costs no memory before its pairs are measured.
class ImagePairs {
  public:
    using Visit = std::function<void(const ImagePair &)>;
    /// These pairs, as they are.
    ImagePairs(std::vector<ImagePair> pairs);  // NOLINT: implicit, a list is a source of pairs
    ImagePairs(std::initializer_list<ImagePair> pairs) : ImagePairs(std::vector<ImagePair>(pairs)) {}
    /// `count` pairs that `produce` passes to its argument one by one, in order.
    ImagePairs(std::size_t count, std::function<void(const Visit &)> produce);

    std::size_t size() const { return count_; }
    void for_each(const Visit &visit) const;

  private:
    std::vector<ImagePair> list_;
    std::size_t count_ = 0;
    std::function<void(const Visit &)> produce_;
};

/// A field of ErrorMetrics that reports name, summarise and gate on.
struct CompareMetric {
    const char *key;    ///< spelling on the command line, JSON and CSV key
    const char *label;  ///< table heading
    bool higher_is_better;
    double ErrorMetrics::*value;
    /// What computing it costs beyond the plain sums (ErrorMetrics holds NaN
    /// for SSIM and FLIP unless asked for); Temporal: the previous pair's
    /// error image, so it is undefined for the first pair of a batch.
    enum class Needs { Sums, Ssim, Flip, Temporal } needs;
};

/// Every metric, in the order help texts list them.
const std::vector<CompareMetric> &compare_metrics();
/// The metric spelt `key`, or nullptr when there is none.
const CompareMetric *find_compare_metric(const std::string &key);

/// The pixels to compare: those where `channel` of `image` is non-zero.
struct CompareMask {
    std::string path;  ///< the file it came from, for messages
    AovSet image;
    std::string channel;
};
/// Reads channel `channel` of image `path` (its first channel when empty) as
/// a mask. Throws aaf::InputError "<path>: <problem>" for an unreadable file
/// or a missing channel.
CompareMask read_compare_mask(const std::string &path, const std::string &channel = "");

struct ComparePairResult;

/// What compare_files() measures and writes. The defaults compare R, G, B of
/// the whole images with no metric beyond the plain sums.
struct CompareFilesOptions {
    /// Each "name" (the same channel in both images) or "test=reference"
    /// (e.g. "aaf.V=shadow.V": a filter's output against a reference render's
    /// visibility). A name an image lacks that is a contract channel of a role
    /// (aov_contract.h) is looked up as that role resolves in that image, so R,
    /// G, B find a Blender file's ViewLayer.Combined.R/G/B.
    std::vector<std::string> channels{"R", "G", "B"};
    /// Non-empty: compare every channel of the test image named "<layer>.*"
    /// instead of `channels`; a layer whose channels belong to roles of
    /// different units (shadow.V beside shadow.d1) is refused (InputError).
    std::string layer;
    std::optional<PixelRect> crop;    ///< only pixels inside; must lie within the images
    std::optional<CompareMask> mask;  ///< only pixels where it is non-zero; same size as the images
    /// Metrics to be computed (reported or gated on): SSIM and FLIP run only
    /// when one listed needs them. FLIP is HDR-FLIP for an EXR reference,
    /// LDR-FLIP for display-encoded files (PNG, JPEG, ...).
    std::vector<const CompareMetric *> metrics;
    double psnr_peak = 1.0;                   ///< see CompareOptions::psnr_peak
    float flip_pixels_per_degree = 67.0206f;  ///< 0.7 m from a 0.7 m wide 4K display
    /// Non-empty: the error heatmap PNG of the (single) pair, with its EXR
    /// beside it (write_error_heatmap()); must not end in .exr.
    std::string heatmap;
    /// Files the caller writes from the results (a CSV report). Like the
    /// heatmap, each is refused before anything is read when it names an input.
    std::vector<std::string> report_paths;
    /// Called after each pair is measured, with its index and result (progress).
    std::function<void(std::size_t index, const ComparePairResult &result)> on_pair;
};

/// The measurement of one pair.
struct ComparePairResult {
    ImagePair pair;
    std::vector<std::string> channels;  ///< the channels compared, "test=reference" where the names differ
    ErrorMetrics metrics;
    double spp = std::nan("");  ///< the test image's mean spp over shaded pixels; NaN without those AOVs
};

/// Compares one pair already in memory as compare_files() compares files
/// (`pair` names them in messages and the result; the heatmap is not drawn).
/// Throws as compare_files() does.
ComparePairResult compare_aov_sets(const ImagePair &pair, const AovSet &test, const AovSet &reference,
                                   const CompareFilesOptions &options);

struct CompareFilesResult {
    std::vector<ComparePairResult> pairs;  ///< one per input pair, in order
    float heatmap_scale = 0;               ///< with a heatmap: its colour bar's top (99th percentile)
    double read_seconds = 0;               ///< spent reading the images
    double measure_seconds = 0;            ///< spent computing the metrics
};

/// Reads and compares each pair in turn (compare_images() of
/// error_metrics.h) and writes the heatmap, if asked for. With a Temporal
/// metric asked for, each pair after the first also gets its temporal error
/// against the pair before it (the previous frame of a sequence). Throws
/// aaf::InputError "<file>: <problem>" for an unreadable image, a layer with
/// no channels, a mask of another size or an output that would overwrite an
/// input (checked for each pair before it is read, so before anything is
/// written); errors of the comparison itself (sizes, missing channels, a crop
/// outside the image) are prefixed "<test> vs <reference>: ". Throws
/// aaf::Error for a heatmap with other than one pair.
CompareFilesResult compare_files(const ImagePairs &pairs, const CompareFilesOptions &options);

/// One metric over a batch of pairs.
struct MetricSummary {
    double mean = 0, median = 0;
    double worst = 0;             ///< the largest value, or the smallest where higher is better
    std::size_t worst_index = 0;  ///< the pair it belongs to (the first such pair)
};
/// Whether `metric` has a value for the pair at `pair_index` of a batch: a
/// temporal metric has none for the first.
bool defined_for_pair(const CompareMetric &metric, std::size_t pair_index);
/// The mean, median and worst of `metric` over the `results` it is defined
/// for. Throws aaf::Error when there are none.
MetricSummary summarise(const std::vector<ComparePairResult> &results, const CompareMetric &metric);

/// A pass/fail threshold on a metric.
struct Gate {
    const CompareMetric *metric;
    double limit;
    bool above;  ///< fails when the value is above (else below) the limit; NaN always fails
};
struct GateFailure {
    std::size_t pair_index;  ///< into the results
    Gate gate;
    double value;
};
/// Every (pair, gate) that fails, pairs in order and each pair's gates in
/// order; a gate on a metric not defined for a pair is not checked there.
std::vector<GateFailure> failed_gates(const std::vector<ComparePairResult> &results,
                                      const std::vector<Gate> &gates);

}  // namespace aaf::io
