#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "aaf/core/analysis/spectral_filter.h"
#include "aaf/core/analysis/wedge_metrics.h"
#include "aaf/core/analysis/wedge_spectrum.h"
#include "channel_options.h"
#include "commands.h"

namespace aaf::cli {

namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

struct AnalyzeOptions {
    double s_min = kNone, s_max = kNone;
    std::vector<int> pairs{2, 3, 4};  // MAAF(3), MAAF(5), MAAF(7), the columns of MAAF Table 2
    bool box = false, gauss = false, json = false, no_mu = false;
    int random = 0;
    std::uint64_t seed = 1;
    int grid = WedgeIntegrationGrid{}.cells_per_axis;
};

/// One method's numbers for one wedge, or their means over several.
struct MethodResult {
    std::string name;                 // as the paper names it: AAF, FSF, MAAF(2N-1)
    double coverage = 0;              // MAAF Eq. 15, integrated numerically
    double accuracy = 0;              // MAAF Eq. 14, integrated numerically
    double coverage_eq = kNone;       // boxes: MAAF Eq. 16-18 from the boxes' geometry
    double coverage_printed = kNone;  // boxes: MAAF Eq. 16-18 as printed in the paper
};

std::string maaf_name(int pairs) {
    return "MAAF(" + std::to_string(2 * pairs - 1) + ")";
}

/// MAAF Table 1 (box filters, mean over the paper's 50 random wedges).
double paper_table1(const std::string &name) {
    static const std::map<std::string, double> table = {
        {"AAF", 0.097},     {"FSF", 0.5},        {"MAAF(3)", 0.197},  {"MAAF(5)", 0.275},
        {"MAAF(7)", 0.401}, {"MAAF(25)", 0.677}, {"MAAF(75)", 0.876}, {"MAAF(125)", 0.943}};
    const auto found = table.find(name);
    return found == table.end() ? kNone : found->second;
}

std::vector<MethodResult> analyze(const DoubleWedge &wedge, const AnalyzeOptions &options) {
    const SpectralShape shape = options.gauss ? SpectralShape::Gaussian : SpectralShape::Box;
    WedgeIntegrationGrid grid;
    grid.cells_per_axis = options.grid;
    const auto measured = [&](const std::string &name, const SpectralFilter &filter) {
        const FilterMetrics metrics = integrate_filter_metrics(filter, wedge, grid);
        MethodResult result;
        result.name = name;
        result.coverage = metrics.coverage;
        result.accuracy = metrics.accuracy;
        return result;
    };
    std::vector<MethodResult> results{measured("AAF", aaf_spectral_filter(wedge, shape)),
                                      measured("FSF", fsf_spectral_filter(wedge, shape))};
    if (shape == SpectralShape::Box) {
        results[0].coverage_eq = aaf_box_coverage(wedge);
        results[0].coverage_printed = aaf_box_coverage_as_printed(wedge);
        results[1].coverage_eq = results[1].coverage_printed = fsf_box_coverage();
    }
    for (int pairs : options.pairs) {
        MethodResult result =
            measured(maaf_name(pairs), maaf_spectral_filter(wedge, pairs, shape, !options.no_mu));
        if (shape == SpectralShape::Box) {
            result.coverage_eq = maaf_box_coverage(wedge, pairs);
            result.coverage_printed = maaf_box_coverage_as_printed(wedge, pairs);
        }
        results.push_back(result);
    }
    return results;
}

/// Means of each method's numbers over `wedges` (added in order: deterministic).
std::vector<MethodResult> analyze_mean(const std::vector<DoubleWedge> &wedges,
                                       const AnalyzeOptions &options) {
    std::vector<MethodResult> sum;
    for (const DoubleWedge &wedge : wedges) {
        const std::vector<MethodResult> one = analyze(wedge, options);
        if (sum.empty()) {
            sum = one;
            continue;
        }
        for (std::size_t m = 0; m < sum.size(); ++m) {
            sum[m].coverage += one[m].coverage;
            sum[m].accuracy += one[m].accuracy;
            sum[m].coverage_eq += one[m].coverage_eq;
            sum[m].coverage_printed += one[m].coverage_printed;
        }
    }
    for (MethodResult &result : sum) {
        const double n = double(wedges.size());
        result.coverage /= n;
        result.accuracy /= n;
        result.coverage_eq /= n;
        result.coverage_printed /= n;
    }
    return sum;
}

nlohmann::ordered_json to_json(const std::vector<MethodResult> &results) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (const MethodResult &r : results) {
        nlohmann::ordered_json entry = {{"coverage", r.coverage}, {"accuracy", r.accuracy}};
        if (!std::isnan(r.coverage_eq)) {
            entry["coverage_eq16_18"] = r.coverage_eq;
            entry["coverage_eq16_18_as_printed"] = r.coverage_printed;
        }
        out[r.name] = entry;
    }
    return out;
}

void print_table(const std::vector<MethodResult> &results, const AnalyzeOptions &options) {
    const bool box = !options.gauss, paper = box && options.random > 0;
    std::printf("%-10s %9s %9s", "method", "coverage", "accuracy");
    if (box) std::printf(" %14s %12s", "MAAF Eq. 16-18", "as printed");
    if (paper) std::printf(" %14s", "paper Table 1");
    std::printf("\n");
    for (const MethodResult &r : results) {
        std::printf("%-10s %9.4f %9.4f", r.name.c_str(), r.coverage, r.accuracy);
        if (box) std::printf(" %14.4f %12.4f", r.coverage_eq, r.coverage_printed);
        if (paper) {
            const double value = paper_table1(r.name);
            if (std::isnan(value))
                std::printf(" %14s", "-");
            else
                std::printf(" %14.3f", value);
        }
        std::printf("\n");
    }
}

void run_wedge(const AnalyzeOptions &options) {
    const bool have_slopes = !std::isnan(options.s_min) || !std::isnan(options.s_max);
    if (options.random > 0 && have_slopes)
        throw UsageError("--random draws its own wedges: drop --smin and --smax");
    if (options.random == 0 && (std::isnan(options.s_min) || std::isnan(options.s_max)))
        throw UsageError("give --smin and --smax (or --random COUNT)");
    if (options.random == 0 && !(options.s_min < options.s_max))
        throw UsageError("--smin " + CLI::detail::to_string(options.s_min) + " must be below --smax " +
                         CLI::detail::to_string(options.s_max));
    if (options.grid % 2 != 0) throw UsageError("--grid " + std::to_string(options.grid) + " must be even");

    const char *shape = !options.gauss ? "box" : options.no_mu ? "Gaussian (MAAF with mu_p = 1)" : "Gaussian";
    std::vector<MethodResult> results;
    if (options.random > 0) {
        results = analyze_mean(uniform_sorted_wedges(options.random, options.seed), options);
        if (!options.json)
            std::printf(
                "Mean over %d random wedges, s_min < s_max the sorted pair of two uniform draws on "
                "(0, 10), seed %llu; %s filters; grid %d x %d\n",
                options.random, static_cast<unsigned long long>(options.seed), shape, options.grid,
                options.grid);
    } else {
        DoubleWedge wedge;
        wedge.s_min = options.s_min;
        wedge.s_max = options.s_max;
        results = analyze(wedge, options);
        if (!options.json)
            std::printf("Double wedge s_min %g, s_max %g (Omega_y^max 1); %s filters; grid %d x %d\n",
                        options.s_min, options.s_max, shape, options.grid, options.grid);
    }
    if (options.json)
        std::printf("%s\n", to_json(results).dump(2).c_str());
    else
        print_table(results, options);
}

}  // namespace

void add_analyze_command(CLI::App &app) {
    CLI::App *analyze_cmd =
        app.add_subcommand("analyze", "Fourier-domain analyses of the filters (no images read or written)");
    analyze_cmd->require_subcommand(1);
    auto options = std::make_shared<AnalyzeOptions>();
    CLI::App *cmd =
        analyze_cmd->add_subcommand("wedge",
                                    "Accuracy (MAAF Eq. 14) and coverage (MAAF Eq. 15; MAAF Eq. 16-18 for "
                                    "boxes) of AAF, FSF and MAAF on the "
                                    "flatland double wedge between slopes s_min and s_max, Omega_y^max = 1");
    // Past 1e-100 or 1e100, the spectra's squared widths (1 / s_min - 1 / s_max)^2 leave double's range.
    cmd->add_option("--smin", options->s_min, "Smallest wedge slope s_min (d1/d2 - 1), in [1e-100, 1e100]")
        ->check(finite_number(1e-100, 1e100, /*low_allowed=*/true));
    cmd->add_option("--smax", options->s_max, "Largest wedge slope s_max, > s_min, in [1e-100, 1e100]")
        ->check(finite_number(1e-100, 1e100, /*low_allowed=*/true));
    cmd->add_option("--filters", options->pairs,
                    "MAAF's N, the component pairs counting the central filter; each N gives MAAF(2N-1), "
                    "2N-1 filters (comma-separated list)")
        ->delimiter(',')
        ->check(CLI::Range(1, 500))
        ->capture_default_str();
    CLI::Option *box =
        cmd->add_flag("--box", options->box, "Box and parallelogram filters (the default; Table 1)");
    CLI::Option *gauss = cmd->add_flag("--gauss", options->gauss,
                                       "Gaussian filters weighted by mu_p (MAAF Eq. 2, 4, 9-10; Table 2)");
    box->excludes(gauss);
    cmd->add_flag("--no-mu", options->no_mu,
                  "With --gauss: MAAF's components unweighted (mu_p = 1) instead of MAAF Eq. 10's weights")
        ->needs(gauss);
    cmd->add_option("--random", options->random,
                    "Average over this many random wedges 0 < s_min < s_max < 10 (sorted pairs of two "
                    "uniform draws)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--seed", options->seed, "Seed of --random")
        ->check(non_negative_seed())
        ->capture_default_str();
    cmd->add_option("--grid", options->grid, "Midpoint cells per axis of the integration grids (even)")
        ->check(CLI::Range(16, 16384))
        ->capture_default_str();
    cmd->add_flag("--json", options->json,
                  "Print one JSON object keyed by method (AAF, FSF, MAAF(2N-1)), each with coverage and "
                  "accuracy (and, for boxes, MAAF Eq. 16-18)");
    cmd->callback([options] { run_wedge(*options); });
}

}  // namespace aaf::cli
